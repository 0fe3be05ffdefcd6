// Mean and Gaussian curvature per mesh vertex, from the surface's analytic normals: on each
// triangle the shape operator S (dn = S dp, a symmetric 2 × 2 tensor in the triangle's
// plane) is fitted by least squares to its three edges and the normal changes along them
// (Rusinkiewicz, "Estimating curvatures and their derivatives on triangle meshes", 2004,
// first step); H = tr S / 2 and K = det S, averaged at each vertex weighted by area. The
// normals come from the engine's exact first derivatives, so the estimate is first-order
// in the mesh spacing and does not depend on how flat the triangles lie. No DOM here
// (web/test/curvature.test.ts).

export interface Curvatures {
  /** Mean curvature: positive on a sphere whose normals point outward. */
  mean: Float32Array;
  gaussian: Float32Array;
}

export function vertexCurvatures(positions: ArrayLike<number>, normals: ArrayLike<number>, indices: ArrayLike<number>): Curvatures {
  const n = positions.length / 3;
  const mean = new Float32Array(n);
  const gaussian = new Float32Array(n);
  const weight = new Float32Array(n);
  const p = [0, 0, 0].map(() => [0, 0, 0]);
  const q = [0, 0, 0].map(() => [0, 0, 0]);
  const sub = (a: number[], b: number[]) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a: number[], b: number[]) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  for (let t = 0; t < indices.length; t += 3) {
    for (let j = 0; j < 3; ++j) {
      const v = indices[t + j];
      for (let c = 0; c < 3; ++c) {
        p[j][c] = positions[3 * v + c];
        q[j][c] = normals[3 * v + c];
      }
    }
    const e0 = sub(p[1], p[0]);
    const fn = cross(e0, sub(p[2], p[0]));
    const area2 = Math.hypot(fn[0], fn[1], fn[2]);
    const len0 = Math.hypot(e0[0], e0[1], e0[2]);
    if (area2 <= 0 || len0 <= 0) continue; // a collapsed triangle (a pole)
    // The triangle's frame: u along its first edge, w in its plane.
    const u = e0.map((x) => x / len0);
    const nn = fn.map((x) => x / area2);
    const w = cross(nn, u);
    // Normal equations of: for each edge e with normal change d,
    // [eu ew 0; 0 eu ew] [a b c]^T = [du dw]  (S = [a b; b c]).
    let m00 = 0, m01 = 0, m11 = 0, m12 = 0, m22 = 0, r0 = 0, r1 = 0, r2 = 0;
    for (let j = 0; j < 3; ++j) {
      const e = sub(p[(j + 1) % 3], p[j]);
      const d = sub(q[(j + 1) % 3], q[j]);
      const eu = dot(e, u), ew = dot(e, w), du = dot(d, u), dw = dot(d, w);
      m00 += eu * eu;
      m01 += eu * ew;
      m11 += ew * ew + eu * eu;
      m12 += ew * eu;
      m22 += ew * ew;
      r0 += du * eu;
      r1 += du * ew + dw * eu;
      r2 += dw * ew;
    }
    // Solve [m00 m01 0; m01 m11 m12; 0 m12 m22] x = r (symmetric, tridiagonal).
    const det = m00 * (m11 * m22 - m12 * m12) - m01 * m01 * m22;
    if (!(Math.abs(det) > 0)) continue;
    const a = (r0 * (m11 * m22 - m12 * m12) - m01 * (r1 * m22 - m12 * r2)) / det;
    const b = (m00 * (r1 * m22 - m12 * r2) - r0 * m01 * m22) / det;
    const c = (m00 * (m11 * r2 - m12 * r1) - m01 * (m01 * r2) + r0 * m01 * m12) / det;
    // dn = S dp: on a sphere of radius R with outward normals S = I / R, so H = 1/R.
    const h = (a + c) / 2;
    const k = a * c - b * b;
    const wgt = area2 / 2;
    for (let j = 0; j < 3; ++j) {
      const v = indices[t + j];
      mean[v] += wgt * h;
      gaussian[v] += wgt * k;
      weight[v] += wgt;
    }
  }
  for (let v = 0; v < n; ++v)
    if (weight[v] > 0) {
      mean[v] /= weight[v];
      gaussian[v] /= weight[v];
    }
  return { mean, gaussian };
}

/** The fraction of values the colour scale covers: the rest (spikes at poles and creases)
 * saturate at its ends. */
export const CURVATURE_QUANTILE = 0.98;

/** A range symmetric about 0 holding CURVATURE_QUANTILE of |values| (0 for a flat mesh). */
export function symmetricRange(values: ArrayLike<number>): number {
  if (values.length === 0) return 0;
  const abs = Float32Array.from(values, Math.abs).sort();
  return abs[Math.min(abs.length - 1, Math.floor(CURVATURE_QUANTILE * (abs.length - 1)))];
}

/** Blue (negative) through near-white (0) to red (positive), saturating at ±range. */
export function curvatureColors(values: ArrayLike<number>, range: number, out: Float32Array<ArrayBufferLike> = new Float32Array(3 * values.length)): Float32Array<ArrayBufferLike> {
  const neg = [0.17, 0.37, 0.75], mid = [0.95, 0.95, 0.95], pos = [0.77, 0.2, 0.17];
  for (let i = 0; i < values.length; ++i) {
    const t = range > 0 ? Math.max(-1, Math.min(1, values[i] / range)) : 0;
    const end = t < 0 ? neg : pos;
    const s = Math.abs(t);
    for (let c = 0; c < 3; ++c) out[3 * i + c] = mid[c] + (end[c] - mid[c]) * s;
  }
  return out;
}
