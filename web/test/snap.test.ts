// Snapping a drag (snap.ts): the nearest vertex and outline point on screen, the surface
// under the pointer, the frames' outline segments that stay put, and a typed distance.
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { nearestOnSegments, nearestVertex, onAxisTo, onSurface, outlineSegments, snapped, surfaceSnapshot, typedOffset } from '../src/snap';
import type { Basis } from '../src/orientation';
import type { Projector } from '../src/snap';

/** A view from above, 100 pixels a unit: (x, y) at client (100 x, -100 y), rays straight down. */
const top: Projector = {
  toClient: (p) => ({ x: 100 * p.x, y: -100 * p.y, visible: true }),
  ray: (x, y) => new THREE.Ray(new THREE.Vector3(x / 100, -y / 100, 10), new THREE.Vector3(0, 0, -1)),
};
/** Exact to rounding. */
const ROUNDING = 1e-12;

// A unit frame's eight vertices (P1..P8 round it) at z = 0, and a second frame on its right.
const square: Vec3[] = [[0, 0, 0], [0.5, 0, 0], [1, 0, 0], [1, 0.5, 0], [1, 1, 0], [0.5, 1, 0], [0, 1, 0], [0, 0.5, 0]];
const vertices: Vec3[] = [...square, [1.5, 0, 0], [2, 0, 0], [2, 0.5, 0], [2, 1, 0], [1.5, 1, 0]];
const frames = [{ vertices: [0, 1, 2, 3, 4, 5, 6, 7] }, { vertices: [2, 8, 9, 10, 11, 12, 4, 3] }];

describe('nearestVertex', () => {
  it('takes the candidate nearest the pointer on screen, within the pixels given', () => {
    expect(nearestVertex(vertices, [0, 1, 2, 3], top, 95, -4)).toBe(2);
    expect(nearestVertex(vertices, [0, 1, 3], top, 95, -4)).toBeNull(); // 2 is no candidate
    expect(nearestVertex(vertices, [0, 1, 2], top, 80, 0)).toBeNull(); // 20 px from 2
    expect(nearestVertex(vertices, [0, 1, 2], top, 80, 0, 25)).toBe(2);
  });
});

describe('outlineSegments', () => {
  it('lists each side segment once (a shared side too) and none that a moved vertex ends', () => {
    expect(outlineSegments(frames, new Set())).toHaveLength(8 + 8 - 2);
    const kept = outlineSegments(frames, new Set([9]));
    expect(kept).toHaveLength(14 - 2);
    expect(kept.some(([a, b]) => a === 9 || b === 9)).toBe(false);
  });
});

describe('nearestOnSegments', () => {
  it('gives the point of the nearest outline under the pointer, on the segment exactly', () => {
    const segments = outlineSegments(frames, new Set());
    const p = nearestOnSegments(vertices, segments, top, 104, -30)!; // 4 px right of x = 1
    expect(Math.abs(p[0] - 1)).toBeLessThan(ROUNDING);
    expect(Math.abs(p[1] - 0.3)).toBeLessThan(ROUNDING);
    expect(p[2]).toBe(0);
    expect(nearestOnSegments(vertices, segments, top, 130, -30)).toBeNull(); // 20 px off
  });
});

describe('onSurface', () => {
  it('gives the first point of the surface under the pointer, seen from either side', () => {
    // A square at z = 0.5 of two triangles, facing down (the ray meets its back).
    const surface = surfaceSnapshot([0, 0, 0.5, 1, 0, 0.5, 1, 1, 0.5, 0, 1, 0.5], [0, 2, 1, 0, 3, 2]);
    const p = onSurface(surface, top, 25, -75)!;
    expect(p[2]).toBeCloseTo(0.5, 12);
    expect(p[0]).toBeCloseTo(0.25, 12);
    expect(p[1]).toBeCloseTo(0.75, 12);
    expect(onSurface(surface, top, 150, -75)).toBeNull();
  });
});

describe('typedOffset', () => {
  it('is the distance along the locked axis, else along the drag with that length', () => {
    expect(typedOffset(-0.25, [0, 1, 0], [5, 5, 5])).toEqual([0, -0.25, 0]);
    // A local axis: the distance along it.
    const local = typedOffset(2, [0.6, 0.8, 0], [1, 0, 0])!;
    [1.2, 1.6, 0].forEach((x, c) => expect(Math.abs(local[c] - x)).toBeLessThan(ROUNDING));
    const d = typedOffset(10, null, [3, 4, 0])!;
    [6, 8, 0].forEach((x, c) => expect(Math.abs(d[c] - x)).toBeLessThan(ROUNDING));
    expect(typedOffset(1, null, [0, 0, 0])).toBeNull();
  });
});

describe('snapped and onAxisTo', () => {
  it('rounds the offset along the global axes, or along a basis, to the step', () => {
    expect(snapped([0.26, -0.13, 0.0001], 0.25)).toEqual([0.25, -0.25, 0]);
    expect(snapped([0.26, -0.13, 0.0001], 0)).toEqual([0.26, -0.13, 0.0001]);
    // The basis turned 45° about z: an offset of 0.3 along its x' rounds to 0.25 along x'.
    const r = Math.SQRT1_2;
    const turned: Basis = [
      [r, r, 0],
      [-r, r, 0],
      [0, 0, 1],
    ];
    const d = snapped([0.3 * r + 0.01 * r, 0.3 * r - 0.01 * r, 0], 0.25, turned);
    [0.25 * r, 0.25 * r, 0].forEach((x, c) => expect(Math.abs(d[c] - x)).toBeLessThan(ROUNDING));
  });
  it('lines the vertex up with a snap target along the locked axis', () => {
    // Locked to x from (1, 2, 3): a target at (4, 7, -1) puts it at x = 4, y and z kept.
    expect(onAxisTo([1, 2, 3], [1, 0, 0], [4, 7, -1])).toEqual([3, 0, 0]);
    // Along a local axis: the target's projection on it.
    const d = onAxisTo([0, 0, 0], [0.6, 0.8, 0], [1, 2, 5]);
    [0.6 * 2.2, 0.8 * 2.2, 0].forEach((x, c) => expect(Math.abs(d[c] - x)).toBeLessThan(ROUNDING));
  });
});
