// Symmetric modelling: the panel's mirror plane (x, y or z = 0, or through the model's centre)
// and what a move of some vertices does to their mirror partners. Shared by the handle drag
// (drag.ts), the move gizmo (gizmo.ts) and the panel's move, scale and rotate (modeller.ts).
// No DOM: web/test runs it in Node.
import type { Vec3 } from './api';

/** A vertex is on the mirror plane, or at the mirrored place of another, within this fraction
 * of the model's bounding-box diagonal (a model built symmetric to rounding, or by typed
 * numbers, is well inside; a designer's freehand model may need its halves snapped first). */
export const MIRROR_TOLERANCE = 1e-6;

/** A mirror plane: where coordinate `axis` equals `at`. */
export interface MirrorPlane {
  axis: 0 | 1 | 2;
  at: number;
}

/** The bounding box of points: lowest and highest corner. */
function bounds(points: readonly Vec3[]): { lo: number[]; hi: number[] } {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const p of points) for (let c = 0; c < 3; ++c) (lo[c] = Math.min(lo[c], p[c])), (hi[c] = Math.max(hi[c], p[c]));
  return { lo, hi };
}

/** The plane the panel's *symmetry* names: 'x', 'y', 'z' (through the origin) or 'cx', 'cy',
 * 'cz' (through the centre of the model's bounding box, as it is when asked); null when off. */
export function symmetryPlane(choice: string, vertices: readonly Vec3[]): MirrorPlane | null {
  const centred = choice.startsWith('c');
  const axis = ['x', 'y', 'z'].indexOf(centred ? choice.slice(1) : choice);
  if (axis < 0) return null;
  if (!centred) return { axis: axis as 0 | 1 | 2, at: 0 };
  const { lo, hi } = bounds(vertices);
  return { axis: axis as 0 | 1 | 2, at: (lo[axis] + hi[axis]) / 2 };
}

/** `p` mirrored across the plane. */
export function mirrored(p: readonly number[], plane: MirrorPlane): Vec3 {
  const q: Vec3 = [p[0], p[1], p[2]];
  q[plane.axis] = 2 * plane.at - p[plane.axis];
  return q;
}

/** What a move of the vertices `moved` (at `from`) takes along across the plane: which of
 * them lie on it (they stay on it), and their mirror partners not among them (each the vertex
 * nearest the mirrored place, within MIRROR_TOLERANCE of the diagonal) with the index into
 * `moved` of the vertex each mirrors. Computed once per drag, at its start. */
export function mirrorPartners(
  vertices: readonly Vec3[],
  moved: readonly number[],
  from: readonly Vec3[],
  plane: MirrorPlane,
): { onPlane: boolean[]; partners: number[]; source: number[] } {
  const { lo, hi } = bounds(vertices);
  const tolerance = MIRROR_TOLERANCE * Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 1e-300);
  const taken = new Set(moved);
  const onPlane = from.map((p) => Math.abs(p[plane.axis] - plane.at) <= tolerance);
  const partners: number[] = [];
  const source: number[] = [];
  from.forEach((p, i) => {
    if (onPlane[i]) return;
    const m = mirrored(p, plane);
    let best = -1, bestDistance = tolerance;
    vertices.forEach((q, v) => {
      const dist = Math.hypot(q[0] - m[0], q[1] - m[1], q[2] - m[2]);
      if (dist <= bestDistance) (best = v), (bestDistance = dist);
    });
    if (best >= 0 && !taken.has(best)) {
      taken.add(best);
      partners.push(best);
      source.push(i);
    }
  });
  return { onPlane, partners, source };
}

/** A symmetric move: the moved vertices put at `to` (those on the plane kept on it), and
 * their partners at the mirror images of where their vertices went. Any map (a move, a turn,
 * a scale) stays symmetric so. */
export function symmetricMove(
  plane: MirrorPlane,
  found: ReturnType<typeof mirrorPartners>,
  moved: readonly number[],
  to: readonly Vec3[],
): { vertices: number[]; positions: Vec3[] } {
  const positions = to.map((p, i) => {
    const q: Vec3 = [p[0], p[1], p[2]];
    if (found.onPlane[i]) q[plane.axis] = plane.at;
    return q;
  });
  return {
    vertices: [...moved, ...found.partners],
    positions: [...positions, ...found.source.map((i) => mirrored(positions[i], plane))],
  };
}
