// The transform orientation (the panel's *axes*, as Blender's): the axes that the move gizmo,
// the rotate and scale gizmo, an axis-locked handle drag (X, Y, Z) and the selection's typed
// move and rotate use: global (x, y, z), local (the selected frame's own: u, v and the normal
// of the two) or normal (the surface normal at the selection as the third axis). No DOM:
// web/test runs it in Node.
import type { Model, Vec3 } from './api';
import { rotatedAbout } from './selection-transform';

export type Orientation = 'global' | 'local' | 'normal';

/** Three orthonormal, right-handed axes (x', y', z' = x' × y'), each a unit vector in world
 * coordinates. */
export type Basis = [Vec3, Vec3, Vec3];

export const GLOBAL_BASIS: Basis = [
  [1, 0, 0],
  [0, 1, 0],
  [0, 0, 1],
];

/** At most this many of the selection's vertices are looked up on the mesh for its normal (an
 * even pick of them: a select-all on a large model stays a few milliseconds). */
export const NORMAL_SAMPLES = 16;

const dot = (a: readonly number[], b: readonly number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: readonly number[], b: readonly number[]): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const unit = (a: readonly number[]): Vec3 | null => {
  const n = Math.hypot(a[0], a[1], a[2]);
  return n > 1e-300 && Number.isFinite(n) ? [a[0] / n, a[1] / n, a[2] / n] : null;
};

/** The right-handed basis whose z' is `z` and whose x' is `x` made perpendicular to it (the
 * global x, else y, where `x` is parallel to `z` or null); null when `z` is 0. */
export function basisFrom(z: readonly number[], x: readonly number[] | null): Basis | null {
  const w = unit(z);
  if (!w) return null;
  for (const hint of [x, [1, 0, 0], [0, 1, 0]]) {
    if (!hint) continue;
    const u = unit(hint.map((c, i) => c - dot(hint, w) * w[i]));
    if (u && Math.abs(dot(unit(hint) ?? [0, 0, 0], w)) < 1 - 1e-9) return [u, cross(w, u), w];
  }
  return null;
}

/** A frame's own axes: x' along its u (from side u = 0 to u = 1, the mean of its two
 * v-sides), z' the normal of its u and v directions, y' = z' × x' (its v made perpendicular).
 * Slots as in structure.ts: 0 (0,0), 2 (1,0), 4 (1,1), 6 (0,1). */
export function frameBasis(vertices: readonly Vec3[], ring: readonly number[]): Basis | null {
  const p = (slot: number) => vertices[ring[slot]];
  const u = [0, 1, 2].map((c) => p(2)[c] - p(0)[c] + p(4)[c] - p(6)[c]);
  const v = [0, 1, 2].map((c) => p(6)[c] - p(0)[c] + p(4)[c] - p(2)[c]);
  return basisFrom(cross(u, v), u);
}

/** The mean of the mesh's normals at the mesh vertices nearest the given points (one linear
 * pass over the mesh), or null when the mesh is empty or the normals cancel. */
export function meshNormalNear(positions: ArrayLike<number>, normals: ArrayLike<number>, points: readonly Vec3[]): Vec3 | null {
  const n = positions.length / 3;
  if (!n || !points.length) return null;
  const best = points.map(() => ({ distance: Infinity, at: -1 }));
  for (let i = 0; i < n; ++i) {
    const x = positions[3 * i], y = positions[3 * i + 1], z = positions[3 * i + 2];
    points.forEach((q, k) => {
      const d = (x - q[0]) ** 2 + (y - q[1]) ** 2 + (z - q[2]) ** 2;
      if (d < best[k].distance) best[k] = { distance: d, at: i };
    });
  }
  const sum = [0, 0, 0];
  for (const { at } of best) for (let c = 0; c < 3; ++c) sum[c] += normals[3 * at + c];
  return unit(sum);
}

/** Up to `count` of the items, evenly spread (all of them when fewer). */
export function evenPick<T>(items: readonly T[], count: number): T[] {
  if (items.length <= count) return [...items];
  return Array.from({ length: count }, (_, i) => items[Math.floor((i * items.length) / count)]);
}

/** What the orientation of a selection is taken from. */
export interface OrientationSource {
  model: Model;
  /** The vertices the tools act on (the selected ones, else the selected frames'). */
  vertices: readonly number[];
  /** The selected frames, and the active vertex (the one picked last), if any. */
  frames: readonly number[];
  active: number | null;
  /** The surface (for the normal); null: none yet. */
  mesh: { positions: ArrayLike<number>; normals: ArrayLike<number> } | null;
}

/** The frame whose axes are the selection's local ones: the first selected frame, else the
 * first frame that uses the active vertex (else the first of the selection's vertices). */
export function localFrame(s: OrientationSource): number | null {
  if (s.frames.length) return Math.min(...s.frames);
  const vertex = s.active ?? s.vertices[0];
  if (vertex === undefined) return null;
  const k = s.model.frames.findIndex((f) => f.vertices.includes(vertex));
  return k < 0 ? null : k;
}

/** The axes of `orientation` for the selection: global; the local frame's (localFrame); or the
 * surface normal at the selection's vertices (NORMAL_SAMPLES of them) as z', x' the local
 * frame's u made perpendicular to it. Falls back to global where the selection has no frame
 * (and to local where there is no mesh). */
export function selectionBasis(orientation: Orientation, s: OrientationSource): Basis {
  if (orientation === 'global') return GLOBAL_BASIS;
  const k = localFrame(s);
  const local = k === null ? null : frameBasis(s.model.vertices, s.model.frames[k].vertices);
  if (orientation === 'local' || !s.mesh) return local ?? GLOBAL_BASIS;
  const points = evenPick(s.vertices.length ? s.vertices : k === null ? [] : s.model.frames[k].vertices, NORMAL_SAMPLES);
  const normal = meshNormalNear(s.mesh.positions, s.mesh.normals, points.map((v) => s.model.vertices[v]));
  return (normal && basisFrom(normal, local ? local[0] : null)) ?? local ?? GLOBAL_BASIS;
}

/** A world vector's components along the basis' axes. */
export function toBasis(d: readonly number[], b: Basis): Vec3 {
  return [dot(d, b[0]), dot(d, b[1]), dot(d, b[2])];
}

/** The world vector of components `c` along the basis' axes. */
export function fromBasis(c: readonly number[], b: Basis): Vec3 {
  return [0, 1, 2].map((i) => c[0] * b[0][i] + c[1] * b[1][i] + c[2] * b[2][i]) as Vec3;
}

/** Whether the basis is the global one (its numbers are kept exact there). */
export const isGlobal = (b: Basis) => b.every((axis, i) => axis.every((x, c) => x === (i === c ? 1 : 0)));

/** The points turned by `degrees` about the axis `axis` (a unit vector) through `centre`
 * (right-handed). Along a global axis exactly as rotatedAbout (quarter turns exact). */
export function rotatedAboutAxis(points: readonly Vec3[], centre: Vec3, axis: Vec3, degrees: number): Vec3[] {
  const k = axis.findIndex((x) => x === 1);
  if (k >= 0 && axis.every((x, c) => c === k || x === 0)) return rotatedAbout(points, centre, 'xyz'[k] as 'x' | 'y' | 'z', degrees);
  const a = (degrees * Math.PI) / 180, cos = Math.cos(a), sin = Math.sin(a);
  return points.map((p) => {
    // Rodrigues: r cos + (k × r) sin + k (k · r)(1 − cos).
    const r = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
    const kr = cross(axis, r), along = dot(axis, r) * (1 - cos);
    return [0, 1, 2].map((c) => centre[c] + r[c] * cos + kr[c] * sin + axis[c] * along) as Vec3;
  });
}

/** `p` scaled about `centre` by `factors` along the basis' axes. */
export function scaledAlong(p: readonly number[], centre: readonly number[], b: Basis, factors: readonly number[]): Vec3 {
  const c = toBasis([p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]], b);
  const d = fromBasis([c[0] * factors[0], c[1] * factors[1], c[2] * factors[2]], b);
  return [centre[0] + d[0], centre[1] + d[1], centre[2] + d[2]];
}

/** `p` turned about `centre` by the unit quaternion (x, y, z, w). */
export function turnedBy(p: readonly number[], centre: readonly number[], q: readonly number[]): Vec3 {
  const [x, y, z, w] = q;
  const r = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
  // r + 2w (q × r) + 2 q × (q × r)
  const t = cross([x, y, z], r).map((c) => 2 * c);
  const u = cross([x, y, z], t);
  return [0, 1, 2].map((c) => centre[c] + r[c] + w * t[c] + u[c]) as Vec3;
}

/** The turn of the unit quaternion (x, y, z, w) as an axis (a unit vector) and an angle in
 * degrees (0 to 180, the axis flipped for the shorter way round), the form the server's
 * transforms take; a turn smaller than rounding has angle 0 about z. */
export function axisAngleOf(q: readonly number[]): { axis: Vec3; degrees: number } {
  const sign = q[3] < 0 ? -1 : 1; // q and −q are one turn: the one with w ≥ 0 turns ≤ 180°
  const v = [sign * q[0], sign * q[1], sign * q[2]];
  const axis = unit(v);
  const s = Math.hypot(v[0], v[1], v[2]);
  if (!axis || s < 1e-15) return { axis: [0, 0, 1], degrees: 0 };
  return { axis, degrees: (2 * Math.atan2(s, sign * q[3]) * 180) / Math.PI };
}
