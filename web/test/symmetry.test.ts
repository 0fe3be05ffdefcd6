// Symmetric modelling (symmetry.ts): the panel's plane, through the origin or the model's
// centre, the partners of moved vertices, and moves that stay symmetric.
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { mirrored, mirrorPartners, symmetricMove, symmetryPlane } from '../src/symmetry';

/** Exact to rounding (numbers near 1). */
const ROUNDING = 1e-12;

// A row of points symmetric about x = 2 (not about x = 0), and one on that plane.
const points: Vec3[] = [[1, 0, 0], [3, 0, 0], [2, 1, 0], [0.5, 2, 1], [3.5, 2, 1]];

describe('symmetryPlane', () => {
  it('is x, y or z = 0, or through the centre of the box; null when off', () => {
    expect(symmetryPlane('off', points)).toBeNull();
    expect(symmetryPlane('y', points)).toEqual({ axis: 1, at: 0 });
    expect(symmetryPlane('cx', points)).toEqual({ axis: 0, at: 2 });
    expect(symmetryPlane('cz', points)).toEqual({ axis: 2, at: 0.5 });
  });
});

describe('mirrorPartners and symmetricMove', () => {
  it('finds each moved vertex its partner across the centre plane, keeps one on the plane on it', () => {
    const plane = symmetryPlane('cx', points)!;
    const found = mirrorPartners(points, [0, 2, 3], [points[0], points[2], points[3]], plane);
    expect(found.onPlane).toEqual([false, true, false]);
    expect(found.partners).toEqual([1, 4]);
    expect(found.source).toEqual([0, 2]);
    // Any map stays symmetric: here each moved by (0.25, 0.5, -1).
    const to = [points[0], points[2], points[3]].map((p) => [p[0] + 0.25, p[1] + 0.5, p[2] - 1] as Vec3);
    const move = symmetricMove(plane, found, [0, 2, 3], to);
    expect(move.vertices).toEqual([0, 2, 3, 1, 4]);
    expect(move.positions[1]).toEqual([2, 1.5, -1]); // on the plane: x stays 2
    expect(move.positions[3]).toEqual(mirrored(move.positions[0], plane));
    expect(move.positions[4]).toEqual(mirrored(move.positions[2], plane));
    expect(Math.abs(move.positions[3][0] - (4 - 1.25))).toBeLessThan(ROUNDING);
  });

  it('takes no partner that is moved itself, and none farther than the tolerance', () => {
    const plane = symmetryPlane('cx', points)!;
    expect(mirrorPartners(points, [0, 1], [points[0], points[1]], plane).partners).toEqual([]);
    const off: Vec3[] = [[1, 0, 0], [3 + 1e-3, 0, 0]];
    expect(mirrorPartners(off, [0], [off[0]], { axis: 0, at: 2 }).partners).toEqual([]);
  });
});
