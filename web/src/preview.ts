// The adaptive preview: while a drag or slider gesture is in progress the surface is fetched
// at a coarser resolution when the full one has more triangles than software WebGL draws
// at an interactive rate; the gesture's end brings the full resolution back. No DOM here
// (web/test/preview.test.ts).

/** Triangles drawn per update during a gesture at most. Measured on this machine's
 * SwiftShader (docs/performance.md, "Studio: adaptive preview"): ~20k triangles keep a
 * drag update near 30 ms; 65k (the mug at Res 24) take ~160 ms. */
export const PREVIEW_TRIANGLE_BUDGET = 20_000;
/** The pixel density of the surface view during a preview, relative to the screen's: half
 * as many pixels each way, a quarter of the fill of a software renderer. */
export const PREVIEW_PIXEL_SCALE = 0.5;
/** The coarsest preview (samples per patch side): the server's smallest resolution. */
export const PREVIEW_MIN_RESOLUTION = 2;

/** The resolution to show during a gesture: the full one when its mesh (of
 * `fullTriangles`) fits the budget, else the largest whose triangles fit (triangles grow
 * with the square of the resolution), never below PREVIEW_MIN_RESOLUTION. */
export function previewResolution(full: number, fullTriangles: number | null, budget = PREVIEW_TRIANGLE_BUDGET): number {
  if (!fullTriangles || fullTriangles <= budget) return full;
  const scaled = Math.floor((full - 1) * Math.sqrt(budget / fullTriangles)) + 1;
  return Math.max(PREVIEW_MIN_RESOLUTION, Math.min(full, scaled));
}
