// The 3D cursor's placing and keeping, without the DOM (web/test/cursor.test.ts; cursor-tool.ts
// draws it and places it from the pointer and the panel). As Blender's: a point of the scene
// the user puts down, a pivot for rotate and scale (the panel's pivot, selection-transform.ts).
import * as THREE from 'three';
import type { Vec3 } from './api';

/** Where a Shift+right-click puts the cursor: at `hit`, the point of the surface the ray
 * through the pointer meets first, when there is one; else on the plane through the cursor
 * that faces the camera (`viewDirection`, the camera's own), where the ray meets it (the
 * cursor keeps its depth, as Blender's does off the surface); where the ray runs along that
 * plane or away from it, the cursor stays. */
export function cursorFromRay(ray: THREE.Ray, hit: Vec3 | null, cursor: Vec3, viewDirection: THREE.Vector3): Vec3 {
  if (hit) return [...hit];
  const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(viewDirection.clone().normalize(), new THREE.Vector3(...cursor));
  const on = ray.intersectPlane(plane, new THREE.Vector3());
  return on ? (on.toArray() as Vec3) : [...cursor];
}

/** The browser's storage key of the cursors (one per model file, by its path). */
export const CURSOR_STORAGE_KEY = 'pdesurf-studio-cursors';
/** The model files whose cursors are kept: the last ones placed (the oldest go). */
export const CURSOR_FILES_KEPT = 64;

const isPoint = (p: unknown): p is Vec3 =>
  Array.isArray(p) && p.length === 3 && p.every((x) => typeof x === 'number' && Number.isFinite(x));

/** The stored cursors (the storage's text: a JSON object, path to [x, y, z]); anything else,
 * or a value that is no point, is dropped. */
function storedCursors(text: string | null): Record<string, Vec3> {
  let parsed: unknown = null;
  try {
    parsed = text ? JSON.parse(text) : null;
  } catch {
    return {};
  }
  if (!parsed || typeof parsed !== 'object' || Array.isArray(parsed)) return {};
  return Object.fromEntries(Object.entries(parsed).filter(([, p]) => isPoint(p))) as Record<string, Vec3>;
}

/** The cursor stored for the model at `path` (null: none). */
export function storedCursor(text: string | null, path: string): Vec3 | null {
  const p = storedCursors(text)[path];
  return p ? [...p] : null;
}

/** The storage's text with `cursor` kept for `path` (the newest entry; the oldest dropped past
 * CURSOR_FILES_KEPT). */
export function withStoredCursor(text: string | null, path: string, cursor: Vec3): string {
  const all = storedCursors(text);
  delete all[path]; // re-added last: the newest
  all[path] = [...cursor];
  const paths = Object.keys(all);
  for (const old of paths.slice(0, Math.max(0, paths.length - CURSOR_FILES_KEPT))) delete all[old];
  return JSON.stringify(all);
}
