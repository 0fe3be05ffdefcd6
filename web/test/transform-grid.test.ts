import { describe, expect, it } from 'vitest';
import { TRANSFORM_GRIDS, transformGridHtml } from '../src/transform-grid';

/** The test ids a grid's markup holds, in order. */
function testIds(html: string): string[] {
  return [...html.matchAll(/data-testid="([^"]+)"/g)].map((m) => m[1]);
}

describe('transform grids', () => {
  it('the model grid has the ids transform.ts and the e2e tests use, each once', () => {
    expect(testIds(transformGridHtml(TRANSFORM_GRIDS.model))).toEqual([
      'move-x', 'move-y', 'move-z', 'move-apply', 'rotate-axis', 'rotate-degrees', 'rotate-apply', 'scale-factor', 'scale-apply',
    ]);
  });

  it("the curve grid has curve-editor.ts's ids, each once", () => {
    expect(testIds(transformGridHtml(TRANSFORM_GRIDS.curve))).toEqual([
      'curve-move-x', 'curve-move-y', 'curve-move-z', 'curve-move', 'curve-rotate-axis', 'curve-rotate-degrees', 'curve-rotate', 'curve-scale-factor', 'curve-scale',
    ]);
  });

  it('each grid starts with its own rotation and scale', () => {
    expect(transformGridHtml(TRANSFORM_GRIDS.model)).toContain('value="90" title="degrees"');
    expect(transformGridHtml(TRANSFORM_GRIDS.curve)).toContain('value="15" title="degrees"');
    expect(transformGridHtml(TRANSFORM_GRIDS.curve)).toContain('value="1.2" title="factor"');
    expect(transformGridHtml(TRANSFORM_GRIDS.curve)).toContain("axis through the curve's centre");
  });
});
