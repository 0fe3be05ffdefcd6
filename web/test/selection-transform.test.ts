// Scaling and turning the vertex selection about its centre.
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { boxCentre, pivotsOf, rotatedAbout, scaledAbout, selectionPieces, singlePivot } from '../src/selection-transform';

/** Rounding of a few operations on numbers near 1. */
const ROUNDING = 1e-12;

const square: Vec3[] = [
  [1, 1, 2],
  [3, 1, 2],
  [3, 5, 2],
  [1, 5, 2],
];

const close = (a: readonly Vec3[], b: readonly Vec3[]) =>
  a.forEach((p, i) => p.forEach((x, c) => expect(x).toBeCloseTo(b[i][c], 12)));

describe('selection transforms', () => {
  it('pivots about the bounding box centre', () => {
    expect(boxCentre(square)).toEqual([2, 3, 2]);
    expect(boxCentre([[0, 0, 0], [0, 0, 0], [4, 0, 0]])).toEqual([2, 0, 0]); // not the mean
  });

  it('scales distances from the centre by the factor and keeps the centre', () => {
    const c = boxCentre(square);
    const s = scaledAbout(square, c, 1.5);
    expect(boxCentre(s)).toEqual(c);
    expect(s[2][0] - s[0][0]).toBeCloseTo(3, 12);
    expect(s[2][1] - s[0][1]).toBeCloseTo(6, 12);
    close(scaledAbout(s, c, 1 / 1.5), square);
  });

  it('turns right-handed about the axis through the centre, exactly for quarter turns', () => {
    const c = boxCentre(square);
    const r = rotatedAbout(square, c, 'z', 90);
    // (1, 1) is (-1, -2) from the centre: a quarter turn about z takes it to (2, -1).
    expect(r[0]).toEqual([4, 2, 2]);
    expect(r.every((p) => p[2] === 2)).toBe(true);
    // Turns keep distances, and four of 90° (or 3 × 120° about x) come back.
    let back = square;
    for (let i = 0; i < 3; ++i) back = rotatedAbout(back, c, 'x', 120);
    close(back, square);
    const d = (p: Vec3) => Math.hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
    rotatedAbout(square, c, 'y', 33).forEach((p, i) => expect(Math.abs(d(p) - d(square[i]))).toBeLessThan(ROUNDING));
    // About y, z goes toward x.
    expect(rotatedAbout([[0, 0, 1]], [0, 0, 0], 'y', 90)[0]).toEqual([1, 0, 0]);
  });
});

describe('pivots', () => {
  // Two frames apart (vertices 0..3 of one, 4..7 of the other) and a third frame sharing
  // vertex 7 with the second.
  const frames = [{ vertices: [0, 1, 2, 3] }, { vertices: [4, 5, 6, 7] }, { vertices: [7, 8, 9, 10] }];
  it('groups the selection into pieces joined through frames', () => {
    expect(selectionPieces([0, 1, 4, 8], frames)).toEqual([[0, 1], [2, 3]]);
    expect(selectionPieces([2, 9], frames)).toEqual([[0], [1]]);
  });
  it('gives each point its pivot: the box centre, the centre of its piece, the active vertex, the cursor, the origin', () => {
    const points: Vec3[] = [[0, 0, 0], [1, 2, 0], [4, 0, 0], [6, 2, 2]];
    const pieces = [[0, 1], [2, 3]];
    const cursor: Vec3 = [-1, 7, 0.5];
    const none = { active: null, cursor };
    expect(pivotsOf(points, 'centre', pieces, none)).toEqual(points.map(() => [3, 1, 1]));
    expect(pivotsOf(points, 'pieces', pieces, none)).toEqual([[0.5, 1, 0], [0.5, 1, 0], [5, 1, 1], [5, 1, 1]]);
    expect(pivotsOf(points, 'active', pieces, { active: [9, 9, 9], cursor })).toEqual(points.map(() => [9, 9, 9]));
    expect(pivotsOf(points, 'active', pieces, none)).toEqual(points.map(() => [3, 1, 1]));
    expect(pivotsOf(points, 'cursor', pieces, none)).toEqual(points.map(() => cursor));
    expect(pivotsOf(points, 'origin', pieces, none)).toEqual(points.map(() => [0, 0, 0]));
  });
  it('names one place for the active vertex, the cursor and the origin, none for the centres', () => {
    const cursor: Vec3 = [2, 0.5, 0];
    expect(singlePivot('cursor', { active: [1, 1, 1], cursor })).toEqual(cursor);
    expect(singlePivot('active', { active: [1, 1, 1], cursor })).toEqual([1, 1, 1]);
    expect(singlePivot('active', { active: null, cursor })).toBeNull();
    expect(singlePivot('origin', { active: null, cursor })).toEqual([0, 0, 0]);
    expect(singlePivot('centre', { active: [1, 1, 1], cursor })).toBeNull();
    expect(singlePivot('pieces', { active: [1, 1, 1], cursor })).toBeNull();
  });
  it('turns and scales about the cursor: distances to it kept by a turn, multiplied by a scale', () => {
    const cursor: Vec3 = [2, 0.5, 0];
    const pivots = pivotsOf(square, 'cursor', [[0, 1, 2, 3]], { active: null, cursor });
    const turned = square.map((p, i) => rotatedAbout([p], pivots[i], 'z', 90)[0]);
    const scaled = square.map((p, i) => scaledAbout([p], pivots[i], 3)[0]);
    const distance = (p: Vec3) => Math.hypot(p[0] - cursor[0], p[1] - cursor[1], p[2] - cursor[2]);
    square.forEach((p, i) => {
      expect(Math.abs(distance(turned[i]) - distance(p))).toBeLessThan(ROUNDING);
      expect(Math.abs(distance(scaled[i]) - 3 * distance(p))).toBeLessThan(ROUNDING);
    });
    // A quarter turn about z through (2, 0.5): (1, 1) goes to (1.5, -0.5), exactly.
    expect(turned[0]).toEqual([1.5, -0.5, 2]);
  });
});
