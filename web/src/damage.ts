// The frame view's region redraw during a drag (frame-view.ts, FrameView): which line segments
// and point handles may cover a pixel of a screen rectangle. On software WebGL a draw of
// the view costs per primitive, not per pixel (a 1,000-frame sheet: 8,000 segments and
// 3,131 handles, ~17 ms whatever the scissor), and the page's main thread waits for it, so
// a moved handle redraws only the primitives near it (docs/performance.md, "Studio:
// adaptive preview"). No DOM here (web/test/damage.test.ts).

/** A screen rectangle, in CSS pixels from the view's bottom left; empty when x1 < x0. */
export interface Rect {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
}

export const EMPTY_RECT: Readonly<Rect> = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };

/** Points on screen: `xy` [x, y] per point; `wild[i]` when point i lies outside the clip
 * depth range (behind the camera, say), where its primitives' pixels cannot be bounded. */
export interface ScreenPoints {
  xy: Float32Array;
  wild: Uint8Array;
}

/** `rect` grown to hold the square of half-size `radius` around point i (everything, when
 * the point is wild). */
export function addPoint(rect: Rect, points: ScreenPoints, i: number, radius: number): void {
  if (points.wild[i]) {
    Object.assign(rect, { x0: -Infinity, y0: -Infinity, x1: Infinity, y1: Infinity });
    return;
  }
  const x = points.xy[2 * i], y = points.xy[2 * i + 1];
  rect.x0 = Math.min(rect.x0, x - radius);
  rect.y0 = Math.min(rect.y0, y - radius);
  rect.x1 = Math.max(rect.x1, x + radius);
  rect.y1 = Math.max(rect.y1, y + radius);
}

/** Writes into `out` the line vertices (2m, 2m + 1) of every segment m whose box, grown by
 * `pad`, meets `rect` (segment m joins points lineVertex[2m] and lineVertex[2m + 1]; a
 * wild end always meets it); returns how many indices it wrote. In segment order, so the
 * segments drawn overlap as in a whole draw. */
export function segmentsIn(points: ScreenPoints, lineVertex: Uint32Array, rect: Rect, pad: number, out: Uint32Array): number {
  const { xy, wild } = points;
  let n = 0;
  for (let k = 0; k + 1 < lineVertex.length; k += 2) {
    const a = lineVertex[k], b = lineVertex[k + 1];
    if (!wild[a] && !wild[b]) {
      const ax = xy[2 * a], ay = xy[2 * a + 1], bx = xy[2 * b], by = xy[2 * b + 1];
      if (Math.max(ax, bx) + pad < rect.x0 || Math.min(ax, bx) - pad > rect.x1) continue;
      if (Math.max(ay, by) + pad < rect.y0 || Math.min(ay, by) - pad > rect.y1) continue;
    }
    out[n++] = k;
    out[n++] = k + 1;
  }
  return n;
}

/** Writes into `out` every point of the first `count` whose square of half-size `radius`
 * meets `rect` (a wild one always); returns how many it wrote, in point order. */
export function pointsIn(points: ScreenPoints, count: number, rect: Rect, radius: number, out: Uint32Array): number {
  const { xy, wild } = points;
  let n = 0;
  for (let i = 0; i < count; ++i) {
    const x = xy[2 * i], y = xy[2 * i + 1];
    if (!wild[i] && (x + radius < rect.x0 || x - radius > rect.x1 || y + radius < rect.y0 || y - radius > rect.y1)) continue;
    out[n++] = i;
  }
  return n;
}
