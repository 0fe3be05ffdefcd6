// Curvature from analytic normals: a sphere (H = 1/R, K = 1/R²), a cylinder (H = 1/(2R),
// K = 0) and a plane (0, 0), tessellated as latitude-longitude grids with exact normals.
import { describe, expect, it } from 'vitest';
import { curvatureColors, symmetricRange, vertexCurvatures } from '../src/curvature';

/** A grid of (n + 1) × (n + 1) samples of f(s, t) → [point, normal], s and t in [0, 1]. */
function grid(n: number, f: (s: number, t: number) => [number[], number[]]) {
  const positions: number[] = [], normals: number[] = [], indices: number[] = [];
  for (let j = 0; j <= n; ++j)
    for (let i = 0; i <= n; ++i) {
      const [p, q] = f(i / n, j / n);
      positions.push(...p);
      normals.push(...q);
    }
  for (let j = 0; j < n; ++j)
    for (let i = 0; i < n; ++i) {
      const a = j * (n + 1) + i;
      indices.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
    }
  return { positions, normals, indices };
}

/** The estimate's error bound at these grid spacings (first order in the spacing, with a
 * margin): relative to the exact value. */
const RELATIVE_TOLERANCE = 0.02;

const interior = (n: number) => {
  const out: number[] = [];
  for (let j = 2; j <= n - 2; ++j) for (let i = 2; i <= n - 2; ++i) out.push(j * (n + 1) + i);
  return out;
};

describe('vertexCurvatures', () => {
  it('a sphere: H = 1/R, K = 1/R² away from the poles', () => {
    const R = 2, n = 48;
    const g = grid(n, (s, t) => {
      const th = 0.3 + 2.5 * t, ph = 2 * Math.PI * s; // latitude band, away from the poles
      const q = [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
      return [q.map((x) => R * x), q];
    });
    const { mean, gaussian } = vertexCurvatures(g.positions, g.normals, g.indices);
    for (const v of interior(n)) {
      expect(Math.abs(mean[v] - 1 / R)).toBeLessThan(RELATIVE_TOLERANCE / R);
      expect(Math.abs(gaussian[v] - 1 / R ** 2)).toBeLessThan(RELATIVE_TOLERANCE / R ** 2);
    }
  });

  it('a cylinder: H = 1/(2R), K = 0; the sign follows the normals', () => {
    const R = 0.5, n = 40;
    for (const sign of [1, -1]) {
      const g = grid(n, (s, t) => {
        const ph = 2 * Math.PI * s;
        const q = [Math.cos(ph), Math.sin(ph), 0];
        return [[R * q[0], R * q[1], 3 * t], q.map((x) => sign * x)];
      });
      const { mean, gaussian } = vertexCurvatures(g.positions, g.normals, g.indices);
      for (const v of interior(n)) {
        expect(Math.abs(mean[v] - sign / (2 * R))).toBeLessThan(RELATIVE_TOLERANCE / R);
        expect(Math.abs(gaussian[v])).toBeLessThan(RELATIVE_TOLERANCE / R ** 2);
      }
    }
  });

  it('a plane: 0 and 0', () => {
    const g = grid(8, (s, t) => [[s, 2 * t, 0.5 * s], [0, 0, 1]]);
    const { mean, gaussian } = vertexCurvatures(g.positions, g.normals, g.indices);
    expect(Math.max(...Array.from(mean, Math.abs), ...Array.from(gaussian, Math.abs))).toBeLessThan(1e-6);
  });
});

describe('colour scale', () => {
  it('covers all but the largest 2 % of |values|, symmetric about 0', () => {
    const values = Array.from({ length: 100 }, (_, i) => (i % 2 ? -1 : 1) * (i < 98 ? 0.5 : 50));
    expect(symmetricRange(values)).toBe(0.5);
    expect(symmetricRange([])).toBe(0);
  });

  it('maps 0 to near-white, the range ends to blue and red, beyond it saturates', () => {
    const c = curvatureColors([0, -1, 1, 5], 1);
    expect(Array.from(c.subarray(0, 3)).map((x) => +x.toFixed(2))).toEqual([0.95, 0.95, 0.95]);
    expect(c[5]).toBeGreaterThan(c[3]); // blue end
    expect(c[6]).toBeGreaterThan(c[8]); // red end
    expect(Array.from(c.subarray(9, 12))).toEqual(Array.from(c.subarray(6, 9)));
  });
});
