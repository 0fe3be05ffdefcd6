// Snapping a handle drag (drag.ts) onto what is already there: the vertex nearest the pointer
// on screen, the nearest point of a frame's outline, or the surface under the pointer; and the
// distance typed during a drag (as Blender: type a number while dragging, Enter applies); with
// an axis locked, a target lines the vertex up with it along the axis. No DOM: web/test runs it
// in Node.
import * as THREE from 'three';
import type { Vec3 } from './api';
import { fromBasis, toBasis } from './orientation';
import type { Basis } from './orientation';

/** What a drag snaps to (the panel's *snap drags to*). */
export type SnapMode = 'off' | 'vertices' | 'edges' | 'surface';

/** A vertex or an outline is snapped to within this many pixels of the pointer (about a
 * handle and a half: near enough to mean it, far enough to hit without care). */
export const SNAP_PIXELS = 12;

/** What snapping needs of a view: client pixels of a world point, the ray through a client
 * point (viewport.ts). */
export interface Projector {
  toClient(p: THREE.Vector3): { x: number; y: number; visible: boolean };
  ray(clientX: number, clientY: number): THREE.Ray;
}

/** The vertex of `candidates` whose handle is nearest the client point (x, y), within
 * `pixels` of it, or null. */
export function nearestVertex(
  vertices: readonly Vec3[],
  candidates: readonly number[],
  view: Projector,
  x: number,
  y: number,
  pixels = SNAP_PIXELS,
): number | null {
  let best: number | null = null;
  let bestDistance = pixels;
  const p = new THREE.Vector3();
  for (const v of candidates) {
    const s = view.toClient(p.set(...vertices[v]));
    const distance = Math.hypot(s.x - x, s.y - y);
    if (s.visible && distance <= bestDistance) (best = v), (bestDistance = distance);
  }
  return best;
}

/** The segments of the frames' outlines (each pair of neighbouring vertices round a frame,
 * once) that stay where they are while `moving` is dragged: neither end moves. */
export function outlineSegments(frames: readonly { vertices: readonly number[] }[], moving: ReadonlySet<number>): [number, number][] {
  const seen = new Set<string>();
  const out: [number, number][] = [];
  for (const { vertices: ring } of frames)
    ring.forEach((a, i) => {
      const b = ring[(i + 1) % ring.length];
      const key = a < b ? `${a}/${b}` : `${b}/${a}`;
      if (a === b || moving.has(a) || moving.has(b) || seen.has(key)) return;
      seen.add(key);
      out.push([a, b]);
    });
  return out;
}

/** The point of the segments nearest the ray through the client point (x, y) whose client
 * point lies within `pixels` of it (the nearest on screen of those), or null. */
export function nearestOnSegments(
  vertices: readonly Vec3[],
  segments: readonly [number, number][],
  view: Projector,
  x: number,
  y: number,
  pixels = SNAP_PIXELS,
): Vec3 | null {
  const ray = view.ray(x, y);
  const a = new THREE.Vector3(), b = new THREE.Vector3(), on = new THREE.Vector3();
  let best: Vec3 | null = null;
  let bestDistance = pixels;
  for (const [i, j] of segments) {
    ray.distanceSqToSegment(a.set(...vertices[i]), b.set(...vertices[j]), undefined, on);
    const s = view.toClient(on);
    const distance = Math.hypot(s.x - x, s.y - y);
    if (s.visible && distance <= bestDistance) (best = on.toArray() as Vec3), (bestDistance = distance);
  }
  return best;
}

/** The surface as it was when a drag began (positions and triangles copied, so that what the
 * drag moves does not move its own target), for snapping onto it. */
export function surfaceSnapshot(positions: ArrayLike<number>, indices: ArrayLike<number>): THREE.Mesh {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(positions), 3));
  geometry.setIndex(new THREE.BufferAttribute(Uint32Array.from(indices), 1));
  geometry.computeBoundingSphere();
  // Both sides: a patch seen from behind is still the surface under the pointer.
  return new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ side: THREE.DoubleSide }));
}

/** The first point of `surface` under the client point (x, y), or null. */
export function onSurface(surface: THREE.Mesh, view: Projector, x: number, y: number): Vec3 | null {
  const raycaster = new THREE.Raycaster();
  raycaster.ray.copy(view.ray(x, y));
  const hit = raycaster.intersectObject(surface, false)[0];
  return hit ? (hit.point.toArray() as Vec3) : null;
}

/** The characters a distance typed during a drag is made of (an expression: `1/8`, `-0.5`). */
export const TYPED_CHARACTERS = /^[0-9.+\-*/()]$/;

/** The offset a typed distance gives: along the locked axis `axis` (a unit vector; the
 * distance's sign the direction), else along the drag's own direction `direction` (its length
 * the distance); null while the drag has no direction yet. */
export function typedOffset(distance: number, axis: Vec3 | null, direction: readonly number[]): Vec3 | null {
  if (axis !== null) return axis.map((a) => (a === 0 ? 0 : a * distance)) as Vec3;
  const length = Math.hypot(direction[0], direction[1], direction[2]);
  if (!(length > 0)) return null;
  return [0, 1, 2].map((c) => (direction[c] / length) * distance) as Vec3;
}

/** An offset with each component along the basis' axes (global when none) rounded to a
 * multiple of `step` (0: as it is). */
export function snapped(d: readonly number[], step: number, basis: Basis | null = null): Vec3 {
  if (!(step > 0)) return [d[0], d[1], d[2]];
  const round = (c: readonly number[]) => [0, 1, 2].map((i) => Math.round(c[i] / step) * step);
  return basis ? fromBasis(round(toBasis(d, basis)), basis) : (round(d) as Vec3);
}

/** The offset that takes `start` along the locked axis `axis` (a unit vector) to where a
 * snap target `target` lies along it (its projection on the axis through `start`: as
 * Blender's snapping with a constraint, the vertex lines up with the target). */
export function onAxisTo(start: readonly number[], axis: Vec3, target: readonly number[]): Vec3 {
  const t = (target[0] - start[0]) * axis[0] + (target[1] - start[1]) * axis[1] + (target[2] - start[2]) * axis[2];
  return axis.map((a) => (a === 0 ? 0 : a * t)) as Vec3;
}
