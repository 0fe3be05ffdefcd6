// Force regions drawn and changed by hand on a patch: always inside [0, 1]², never empty.
import { describe, expect, it } from 'vitest';
import { forceDisplacement, forceEffectText, MIN_REGION, moveRegion, regionCorners, regionFromCorners, regionOutline, resizeRegion, sharedDisplacements, sharedEffectText, sharedForceOf } from '../src/regions';

describe('force regions from picked points', () => {
  it('spans the two picked points in either order', () => {
    expect(regionFromCorners([0.7, 0.2], [0.3, 0.6])).toEqual([0.3, 0.7, 0.2, 0.6]);
    expect(regionFromCorners([0.3, 0.6], [0.7, 0.2])).toEqual([0.3, 0.7, 0.2, 0.6]);
  });

  it('clamps to the patch and widens a click to the narrowest region', () => {
    expect(regionFromCorners([-0.2, 0.5], [1.3, 0.9])).toEqual([0, 1, 0.5, 0.9]);
    const r = regionFromCorners([0.5, 1], [0.5, 1]);
    expect(r[1] - r[0]).toBeCloseTo(MIN_REGION, 12);
    expect(r[3]).toBe(1); // against the side it touches, still inside
    expect(r[3] - r[2]).toBeCloseTo(MIN_REGION, 12);
  });

  it('resizes by a corner, the opposite one staying', () => {
    const r = [0.2, 0.4, 0.1, 0.5] as const;
    expect(resizeRegion([...r], 2, [0.9, 0.8])).toEqual([0.2, 0.9, 0.1, 0.8]);
    // Dragged past the opposite corner: the region turns over, still valid.
    expect(resizeRegion([...r], 0, [0.6, 0.7])).toEqual([0.4, 0.6, 0.5, 0.7]);
    expect(regionCorners([...r])[1]).toEqual([0.4, 0.1]);
  });

  it('moves whole, stopping at the sides of the patch', () => {
    expect(moveRegion([0.2, 0.4, 0.1, 0.5], [0.3, 0.3], [0.5, 0.2])).toEqual([0.4, 0.6, 0, 0.4]);
    expect(moveRegion([0.2, 0.4, 0.1, 0.5], [0, 0], [2, 2])).toEqual([0.8, 1, 0.6, 1]);
  });

  it('outlines the border counter-clockwise from (u0, v0)', () => {
    const o = regionOutline([0, 1, 0, 0.5], 2);
    expect(o).toEqual([[0, 0], [0.5, 0], [1, 0], [1, 0.25], [1, 0.5], [0.5, 0.5], [0, 0.5], [0, 0.25]]);
  });
});

describe('forceDisplacement', () => {
  it('is -f0 / (pi^2 (a1/Lu^2 + a2/Lv^2)) per coordinate: a positive f0.z dents toward -z', () => {
    const d = forceDisplacement([0, 0, 2], [1, 1, 1], [1, 1, 1], [0.25, 0.75, 0.25, 0.75]);
    expect(d[0]).toBe(0);
    expect(d[1]).toBe(0);
    expect(d[2]).toBeCloseTo(-2 / (Math.PI * Math.PI * 8), 14);
    // A region half as wide in u: four times as stiff along u, so it moves less.
    const narrow = forceDisplacement([0, 0, 2], [1, 1, 1], [1, 1, 1], [0.25, 0.5, 0.25, 0.75]);
    expect(Math.abs(narrow[2])).toBeLessThan(Math.abs(d[2]));
    expect(forceDisplacement([1, 0, 0], [0, 1, 1], [0, 1, 1], [0, 1, 0, 1])[0]).toBeNaN();
  });

  it('says how far and which way', () => {
    expect(forceEffectText([0, 0, -0.025])).toBe('its middle moves by (0, 0, -0.025), 0.025 long, mostly toward −z');
    expect(forceEffectText([0, 0, 0])).toBe('f0 is 0: the region does not move');
    expect(forceEffectText([NaN, 0, 0])).toContain('no solution');
  });
});

describe('shared forces', () => {
  const frame = (a1: [number, number, number]) => ({ vertices: [0, 1, 2, 3, 4, 5, 6, 7], a1 });
  const model = { type: 'vertex-frames', vertices: [], frames: [frame([1, 1, 1]), frame([1, 1, 1]), frame([3, 3, 3])] } as unknown as import('../src/api').Model;
  it("act on each frame whole: the formula with that frame's own a1 and a2 over [0, 1]²", () => {
    const force = { f0: [0, 0, 4] as [number, number, number], frames: [2, 0] };
    expect(sharedForceOf(model, [0, 2])).toBeUndefined();
    const withForce = { ...model, forces: [force] };
    expect(sharedForceOf(withForce, [0, 2])).toBe(force);
    const moves = sharedDisplacements(withForce, force);
    expect(moves.map((m) => m.frame)).toEqual([2, 0]);
    // a1 = a2 = 1, Lu = Lv = 1: −4 / (2π²); with a1 = 3: −4 / (4π²).
    expect(moves[1].d[2]).toBeCloseTo(-4 / (2 * Math.PI ** 2), 12);
    expect(moves[0].d[2]).toBeCloseTo(-4 / (4 * Math.PI ** 2), 12);
    expect(sharedEffectText(withForce, force)).toMatch(/^most on frame 0: its middle moves by \(0, 0, -0\.203\)/);
    const even = { f0: [0, 0, 4] as [number, number, number], frames: [0, 1] };
    expect(sharedEffectText({ ...model, forces: [even] }, even)).toMatch(/^on each of its 2 frames its middle moves by/);
  });
});
