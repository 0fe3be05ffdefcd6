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
