// The transform orientations: a frame's local axes, the surface normal at a selection, and
// the maps that use them (a turn about any axis, a scale along a basis, a quaternion's turn).
import { describe, expect, it } from 'vitest';
import type { Model, Vec3 } from '../src/api';
import { axisAngleOf, basisFrom, frameBasis, fromBasis, GLOBAL_BASIS, meshNormalNear, rotatedAboutAxis, scaledAlong, selectionBasis, toBasis, turnedBy } from '../src/orientation';
import type { Basis } from '../src/orientation';

/** Rounding of a few operations on numbers near 1. */
const ROUNDING = 1e-12;
const near = (a: readonly number[], b: readonly number[]) => a.every((x, i) => Math.abs(x - b[i]) < ROUNDING);

/** One frame of side 1 turned by `degrees` about z, lifted to z = 2 (slots 0..7 round it). */
function turnedFrame(degrees: number): Model {
  const square: Vec3[] = [[0, 0, 2], [0.5, 0, 2], [1, 0, 2], [1, 0.5, 2], [1, 1, 2], [0.5, 1, 2], [0, 1, 2], [0, 0.5, 2]];
  return { type: 'vertex-frames', vertices: rotatedAboutAxis(square, [0, 0, 0], [0, 0, 1], degrees), frames: [{ vertices: [0, 1, 2, 3, 4, 5, 6, 7] }] };
}

const orthonormal = (b: Basis) => {
  for (let i = 0; i < 3; ++i)
    for (let j = 0; j < 3; ++j) {
      const d = b[i][0] * b[j][0] + b[i][1] * b[j][1] + b[i][2] * b[j][2];
      expect(Math.abs(d - (i === j ? 1 : 0))).toBeLessThan(ROUNDING);
    }
  // Right-handed: z' = x' × y'.
  const [x, y, z] = b;
  expect(near(z, [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]])).toBe(true);
};

describe('frameBasis', () => {
  it("is the frame's u, v and normal: turned with the frame", () => {
    const m = turnedFrame(30);
    const b = frameBasis(m.vertices, m.frames[0].vertices)!;
    orthonormal(b);
    const a = Math.PI / 6;
    expect(near(b[0], [Math.cos(a), Math.sin(a), 0])).toBe(true);
    expect(near(b[1], [-Math.sin(a), Math.cos(a), 0])).toBe(true);
    expect(near(b[2], [0, 0, 1])).toBe(true);
  });
});

describe('selectionBasis', () => {
  const m = turnedFrame(30);
  it('is global, the frame of the selection, or the mesh normal there with x along u', () => {
    const source = { model: m, vertices: [0], frames: [], active: 0, mesh: null };
    expect(selectionBasis('global', source)).toBe(GLOBAL_BASIS);
    expect(near(selectionBasis('local', source)[0], [Math.cos(Math.PI / 6), Math.sin(Math.PI / 6), 0])).toBe(true);
    // A mesh whose normal near vertex 0 leans toward +x: z' is it, x' the frame's u made
    // perpendicular; a far mesh vertex (another normal) does not count.
    const tilt = [Math.SQRT1_2, 0, Math.SQRT1_2];
    const mesh = { positions: [0.01, 0, 2, 9, 9, 9], normals: [...tilt, 0, 1, 0] };
    const b = selectionBasis('normal', { ...source, mesh });
    orthonormal(b);
    expect(near(b[2], tilt)).toBe(true);
    expect(b[0][0]).toBeGreaterThan(0);
    // No frame uses the vertex: global.
    const lone: Model = { ...m, vertices: [...m.vertices, [5, 5, 5]] };
    expect(selectionBasis('local', { ...source, model: lone, vertices: [8], active: 8 })).toEqual(GLOBAL_BASIS);
  });
  it('meshNormalNear averages the normals nearest the points', () => {
    const n = meshNormalNear([0, 0, 0, 1, 0, 0], [0, 0, 1, 0, 1, 0], [[0.1, 0, 0], [0.9, 0, 0]])!;
    expect(near(n, [0, Math.SQRT1_2, Math.SQRT1_2])).toBe(true);
    expect(meshNormalNear([], [], [[0, 0, 0]])).toBeNull();
  });
  it('basisFrom falls back to another x where the hint is parallel to z', () => {
    orthonormal(basisFrom([0, 0, 3], [0, 0, 1])!);
    expect(basisFrom([0, 0, 0], null)).toBeNull();
  });
});

describe('maps along a basis', () => {
  const r = Math.SQRT1_2;
  const turned: Basis = [
    [r, r, 0],
    [-r, r, 0],
    [0, 0, 1],
  ];
  it('toBasis and fromBasis are inverse', () => {
    const p: Vec3 = [0.3, -2, 5];
    expect(near(fromBasis(toBasis(p, turned), turned), p)).toBe(true);
  });
  it('scales along the basis only: across it nothing moves', () => {
    // (1, 1, 0) lies on x'; (−1, 1, 0) on y'. Twice along x' about the origin.
    expect(near(scaledAlong([1, 1, 0], [0, 0, 0], turned, [2, 1, 1]), [2, 2, 0])).toBe(true);
    expect(near(scaledAlong([-1, 1, 7], [0, 0, 0], turned, [2, 1, 1]), [-1, 1, 7])).toBe(true);
  });
  it('turns about any axis (Rodrigues), quarter turns about a global one exact', () => {
    expect(rotatedAboutAxis([[2, 1, 0]], [1, 1, 0], [0, 0, 1], 90)).toEqual([[1, 2, 0]]);
    const axis: Vec3 = [r, r, 0];
    const [q] = rotatedAboutAxis([[1, -1, 0]], [0, 0, 0], axis, 90);
    expect(near(q, [0, 0, -Math.SQRT2])).toBe(true);
  });
  it('turnedBy a quaternion is the same turn', () => {
    // A quarter turn about z: (x, y, z, w) = (0, 0, sin 45°, cos 45°).
    expect(near(turnedBy([2, 1, 5], [1, 1, 0], [0, 0, r, r]), [1, 2, 5])).toBe(true);
  });

  it("gives a quaternion's turn as the axis and degrees the server's transforms take", () => {
    // 120° about (1, 1, 1)/√3, and the same turn as −q; the axis-angle form turns as q does.
    const axis: Vec3 = [1 / Math.sqrt(3), 1 / Math.sqrt(3), 1 / Math.sqrt(3)];
    const h = Math.PI / 3; // half of 120°
    const q = [...axis.map((c) => c * Math.sin(h)), Math.cos(h)];
    for (const sign of [1, -1]) {
      const t = axisAngleOf(q.map((c) => sign * c));
      expect(near(t.axis, axis)).toBe(true);
      expect(Math.abs(t.degrees - 120)).toBeLessThan(ROUNDING);
      const p: Vec3 = [0.3, -2, 5], c: Vec3 = [1, 2, 3];
      expect(near(rotatedAboutAxis([p], c, t.axis, t.degrees)[0], turnedBy(p, c, q))).toBe(true);
    }
    expect(axisAngleOf([0, 0, 0, 1])).toEqual({ axis: [0, 0, 1], degrees: 0 });
  });
});
