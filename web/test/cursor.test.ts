// The 3D cursor placed from a ray (on the surface hit, else in the plane facing the camera
// through the cursor) and kept per model file.
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { CURSOR_FILES_KEPT, cursorFromRay, storedCursor, withStoredCursor } from '../src/cursor';

/** Rounding of a ray meeting a plane, numbers near 1. */
const ROUNDING = 1e-12;

describe('the 3D cursor', () => {
  const fromAbove = new THREE.Ray(new THREE.Vector3(0.25, 0.5, 10), new THREE.Vector3(0, 0, -1));
  const down = new THREE.Vector3(0, 0, -1);

  it('goes where the ray meets the surface', () => {
    expect(cursorFromRay(fromAbove, [0.25, 0.5, 0.125], [3, 3, 3], down)).toEqual([0.25, 0.5, 0.125]);
  });

  it('off the surface, goes where the ray meets the plane through it facing the camera (its depth kept)', () => {
    const p = cursorFromRay(fromAbove, null, [3, 3, -2], down);
    [0.25, 0.5, -2].forEach((x, i) => expect(Math.abs(p[i] - x)).toBeLessThan(ROUNDING));
    // A slanted ray and view: the new place is on the ray and in the plane through the cursor.
    const ray = new THREE.Ray(new THREE.Vector3(1, -5, 2), new THREE.Vector3(0.1, 1, -0.2).normalize());
    const facing = new THREE.Vector3(0, 1, -0.1).normalize();
    const cursor: Vec3 = [0.5, 1, 0];
    const q = new THREE.Vector3(...cursorFromRay(ray, null, cursor, facing));
    expect(Math.abs(q.clone().sub(new THREE.Vector3(...cursor)).dot(facing))).toBeLessThan(ROUNDING);
    expect(ray.distanceToPoint(q)).toBeLessThan(ROUNDING);
  });

  it('stays where it is when the ray runs along that plane or away from it', () => {
    const along = new THREE.Ray(new THREE.Vector3(0, 0, 0), new THREE.Vector3(1, 0, 0));
    expect(cursorFromRay(along, null, [1, 2, 3], down)).toEqual([1, 2, 3]);
    const away = new THREE.Ray(new THREE.Vector3(0, 0, 0), new THREE.Vector3(0, 0, 1));
    expect(cursorFromRay(away, null, [1, 2, -3], down)).toEqual([1, 2, -3]);
  });

  it('is kept per model file, the newest files kept, anything else in the storage dropped', () => {
    let text = withStoredCursor(null, 'a.json', [1, 2, 3]);
    text = withStoredCursor(text, 'b.json', [4, 5, 6]);
    text = withStoredCursor(text, 'a.json', [7, 8, 9]);
    expect(storedCursor(text, 'a.json')).toEqual([7, 8, 9]);
    expect(storedCursor(text, 'b.json')).toEqual([4, 5, 6]);
    expect(storedCursor(text, 'c.json')).toBeNull();
    expect(storedCursor('not json', 'a.json')).toBeNull();
    expect(storedCursor('{"a.json": [1, "2", 3], "b.json": [1, 2]}', 'a.json')).toBeNull();
    expect(storedCursor('[1, 2, 3]', 'a.json')).toBeNull();
    for (let i = 0; i < CURSOR_FILES_KEPT; ++i) text = withStoredCursor(text, `m${i}.json`, [i, 0, 0]);
    expect(storedCursor(text, 'b.json')).toBeNull(); // the oldest went
    expect(storedCursor(text, 'a.json')).toBeNull();
    expect(storedCursor(text, `m${CURSOR_FILES_KEPT - 1}.json`)).toEqual([CURSOR_FILES_KEPT - 1, 0, 0]);
    expect(Object.keys(JSON.parse(text))).toHaveLength(CURSOR_FILES_KEPT);
  });
});
