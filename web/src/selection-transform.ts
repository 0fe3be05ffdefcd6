// Scaling and turning a vertex selection about its centre (no DOM: web/test runs it in Node).
// The centre is that of the selection's bounding box, as the whole-model Transform pivots
// about its bounding box's centre.
import type { Vec3 } from './api';

/** The centre of the bounding box of `points` (the origin for none). */
export function boxCentre(points: readonly Vec3[]): Vec3 {
  if (!points.length) return [0, 0, 0];
  const lo = [...points[0]], hi = [...points[0]];
  for (const p of points)
    for (let c = 0; c < 3; ++c) {
      lo[c] = Math.min(lo[c], p[c]);
      hi[c] = Math.max(hi[c], p[c]);
    }
  return [0, 1, 2].map((c) => (lo[c] + hi[c]) / 2) as Vec3;
}

/** The points scaled by `factor` about `centre`. */
export function scaledAbout(points: readonly Vec3[], centre: Vec3, factor: number): Vec3[] {
  return points.map((p) => p.map((x, c) => centre[c] + factor * (x - centre[c])) as Vec3);
}

/** The points turned by `degrees` about the axis through `centre` along x, y or z (right-handed:
 * positive turns x toward y about z). */
export function rotatedAbout(points: readonly Vec3[], centre: Vec3, axis: 'x' | 'y' | 'z', degrees: number): Vec3[] {
  const a = (degrees * Math.PI) / 180;
  // Exact quarter turns (cos 90° is 6e-17 in floating point): typed angles give round numbers.
  const quarter = Math.abs(degrees % 90) === 0;
  const cos = quarter ? Math.round(Math.cos(a)) : Math.cos(a);
  const sin = quarter ? Math.round(Math.sin(a)) : Math.sin(a);
  // The two coordinates the turn mixes, in right-handed order.
  const [i, j] = axis === 'x' ? [1, 2] : axis === 'y' ? [2, 0] : [0, 1];
  return points.map((p) => {
    const q = [...p] as Vec3;
    const x = p[i] - centre[i], y = p[j] - centre[j];
    q[i] = centre[i] + cos * x - sin * y;
    q[j] = centre[j] + sin * x + cos * y;
    return q;
  });
}

/** What the selection's scale and rotate turn about (the panel's *pivot*): the centre of the
 * selection's box, each piece's own centre (Blender's individual origins), the active vertex
 * (the last one picked), the 3D cursor (a point the user places: cursor-tool.ts), or the
 * origin. */
export type Pivot = 'centre' | 'pieces' | 'active' | 'cursor' | 'origin';

/** The places a pivot may need besides the points: the active vertex (null: none, the
 * selection's centre instead) and the 3D cursor. */
export interface PivotPlaces {
  active: Vec3 | null;
  cursor: Vec3;
}

/** The pieces of a selection: its vertices (as indices into `vertices`) grouped by the piece
 * of the model they lie on (frames joined through shared vertices are one piece, as select
 * linked joins them); Blender's individual origins over islands. */
export function selectionPieces(vertices: readonly number[], frames: readonly { vertices: readonly number[] }[]): number[][] {
  const parent = new Map<number, number>();
  const root = (v: number): number => {
    const p = parent.get(v) ?? v;
    if (p === v) return v;
    const r = root(p);
    parent.set(v, r);
    return r;
  };
  for (const frame of frames) for (const v of frame.vertices.slice(1)) parent.set(root(v), root(frame.vertices[0]));
  const pieces = new Map<number, number[]>();
  vertices.forEach((v, i) => pieces.set(root(v), [...(pieces.get(root(v)) ?? []), i]));
  return [...pieces.values()];
}

/** The one pivot of every point, where the choice names one place (the active vertex, the
 * cursor, the origin); null where each point's pivot follows from the points (centres). */
export function singlePivot(pivot: Pivot, places: PivotPlaces): Vec3 | null {
  if (pivot === 'origin') return [0, 0, 0];
  if (pivot === 'cursor') return [...places.cursor];
  if (pivot === 'active' && places.active) return [...places.active];
  return null;
}

/** Each point's pivot: `pieces` groups the points (indices into `points`, selectionPieces);
 * `places` the active vertex's and the cursor's (singlePivot). */
export function pivotsOf(points: readonly Vec3[], pivot: Pivot, pieces: readonly number[][], places: PivotPlaces): Vec3[] {
  const single = singlePivot(pivot, places);
  if (single) return points.map(() => single);
  const out: Vec3[] = points.map(() => [0, 0, 0]);
  for (const piece of pivot === 'pieces' ? pieces : [points.map((_, i) => i)]) {
    const centre = boxCentre(piece.map((i) => points[i]));
    for (const i of piece) out[i] = centre;
  }
  return out;
}
