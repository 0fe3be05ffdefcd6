// The preview schedule: the full resolution when it fits the triangle budget, else the
// largest coarser one that fits, never below the server's minimum.
import { describe, expect, it } from 'vitest';
import { PREVIEW_MIN_RESOLUTION, PREVIEW_TRIANGLE_BUDGET, previewResolution } from '../src/preview';

/** Triangles of a model of `patches` patches at resolution r (r samples a side). */
const triangles = (patches: number, r: number) => patches * 2 * (r - 1) ** 2;

describe('previewResolution', () => {
  it('keeps the full resolution when its mesh fits the budget, or before any mesh', () => {
    expect(previewResolution(24, triangles(10, 24))).toBe(24);
    expect(previewResolution(24, null)).toBe(24);
  });

  it('picks the largest resolution whose triangles fit', () => {
    for (const [patches, full] of [[62, 24], [1000, 16], [62, 64], [300, 32]]) {
      const r = previewResolution(full, triangles(patches, full));
      expect(r).toBeLessThan(full);
      if (r > PREVIEW_MIN_RESOLUTION) expect(triangles(patches, r)).toBeLessThanOrEqual(PREVIEW_TRIANGLE_BUDGET);
      expect(triangles(patches, r + 1)).toBeGreaterThan(PREVIEW_TRIANGLE_BUDGET);
    }
  });

  it('never goes below the minimum', () => {
    expect(previewResolution(16, 1e9)).toBe(PREVIEW_MIN_RESOLUTION);
  });
});
