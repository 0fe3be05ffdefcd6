// The frame view's region redraw: every segment or handle that may cover a pixel of the
// region is drawn (none missed, or the region would show a hole), those far from it are
// not (the point of the region), in the order of a whole draw.
import { describe, expect, it } from 'vitest';
import { EMPTY_RECT, addPoint, pointsIn, segmentsIn } from '../src/damage';
import type { Rect, ScreenPoints } from '../src/damage';

/** A deterministic pseudo-random sequence in [0, 1). */
function random(seed: number): () => number {
  let s = seed >>> 0;
  return () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 32);
}

function screen(coordinates: number[], wild: number[] = []): ScreenPoints {
  const points = { xy: Float32Array.from(coordinates), wild: new Uint8Array(coordinates.length / 2) };
  for (const i of wild) points.wild[i] = 1;
  return points;
}

/** Whether a point lies within `pad` of the rectangle (a pixel the segment may colour). */
const near = (x: number, y: number, r: Rect, pad: number) => x >= r.x0 - pad && x <= r.x1 + pad && y >= r.y0 - pad && y <= r.y1 + pad;

describe('segmentsIn', () => {
  it('keeps every segment passing within pad of the region, in segment order', () => {
    const next = random(7);
    const n = 400;
    const coordinates = Array.from({ length: 2 * n }, () => 500 * next());
    const points = screen(coordinates);
    const lineVertex = Uint32Array.from({ length: 2 * n }, () => Math.floor(next() * n));
    const rect = { x0: 200, y0: 180, x1: 260, y1: 230 };
    const pad = 2;
    const out = new Uint32Array(lineVertex.length);
    const count = segmentsIn(points, lineVertex, rect, pad, out);
    const kept = new Set(Array.from(out.subarray(0, count)));
    let far = 0;
    for (let k = 0; k < lineVertex.length; k += 2) {
      const [a, b] = [lineVertex[k], lineVertex[k + 1]];
      let touches = false;
      for (let t = 0; t <= 1; t += 1 / 512) {
        const x = coordinates[2 * a] + t * (coordinates[2 * b] - coordinates[2 * a]);
        const y = coordinates[2 * a + 1] + t * (coordinates[2 * b + 1] - coordinates[2 * a + 1]);
        touches ||= near(x, y, rect, pad);
      }
      if (touches) expect(kept.has(k) && kept.has(k + 1), `segment ${k / 2}`).toBe(true);
      if (!kept.has(k)) ++far;
    }
    expect(far).toBeGreaterThan(lineVertex.length / 4); // most of the view is not redrawn
    const order = Array.from(out.subarray(0, count));
    expect(order).toEqual([...order].sort((x, y) => x - y));
  });

  it('always keeps a segment with a wild end, never one whose box is beyond the pad', () => {
    const points = screen([0, 0, 10, 0, 100, 100, 104, 100], [3]);
    const lineVertex = Uint32Array.of(0, 1, 2, 3, 1, 2);
    const rect = { x0: 13, y0: -5, x1: 20, y1: 5 };
    const out = new Uint32Array(6);
    const count = segmentsIn(points, lineVertex, rect, 2, out);
    // segment 0 ends 3 px left of the region (pad 2): out; 1 has a wild end; 2 crosses it
    expect(Array.from(out.subarray(0, count))).toEqual([2, 3, 4, 5]);
    expect(segmentsIn(points, lineVertex, rect, 3, out)).toBe(6);
  });
});

describe('pointsIn and addPoint', () => {
  it('keeps the handles whose square meets the region, and wild ones', () => {
    const points = screen([0, 0, 50, 50, 58, 50, 70, 50, 900, 900], [4]);
    const out = new Uint32Array(5);
    const rect = { x0: 40, y0: 40, x1: 60, y1: 60 };
    const count = pointsIn(points, 5, rect, 7, out);
    expect(Array.from(out.subarray(0, count))).toEqual([1, 2, 4]); // point 3 is 10 px right of it
    expect(pointsIn(points, 5, rect, 10, out)).toBe(4); // point 3 now reaches 60
  });

  it('grows a rectangle around points, to everything for a wild one', () => {
    const points = screen([10, 20, 30, 5, 0, 0], [2]);
    const r = { ...EMPTY_RECT };
    addPoint(r, points, 0, 2);
    addPoint(r, points, 1, 2);
    expect(r).toEqual({ x0: 8, y0: 3, x1: 32, y1: 22 });
    addPoint(r, points, 2, 2);
    expect([r.x0, r.y0, r.x1, r.y1]).toEqual([-Infinity, -Infinity, Infinity, Infinity]);
  });
});
