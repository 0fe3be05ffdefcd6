// Force regions [u0, u1, v0, v1] placed and changed by hand on a patch (no DOM: web/test runs
// it in Node): a rectangle from two picked parameter points, a corner dragged, the whole
// region moved; always inside [0, 1]² and never thinner than MIN_REGION.
import type { Model, Region, SharedForce } from './api';

/** The narrowest region side a drag makes (the server refuses an empty one). */
export const MIN_REGION = 0.02;
/** Decimals a region bound is kept to (the file stays readable; 1e-4 of a patch side). */
const REGION_DECIMALS = 4;

export type UV = readonly [number, number];

const clamp01 = (x: number) => Math.min(1, Math.max(0, x));
const round = (x: number) => Number(x.toFixed(REGION_DECIMALS));

/** [lo, hi] from two values, at least MIN_REGION apart and inside [0, 1] (widened away from
 * the side it touches). */
function span(a: number, b: number): [number, number] {
  let lo = clamp01(Math.min(a, b)), hi = clamp01(Math.max(a, b));
  if (hi - lo < MIN_REGION) {
    const mid = Math.min(1 - MIN_REGION / 2, Math.max(MIN_REGION / 2, (lo + hi) / 2));
    lo = mid - MIN_REGION / 2;
    hi = mid + MIN_REGION / 2;
  }
  return [round(lo), round(hi)];
}

/** The region spanned by two picked points of a patch (in any order). */
export function regionFromCorners(a: UV, b: UV): Region {
  const [u0, u1] = span(a[0], b[0]);
  const [v0, v1] = span(a[1], b[1]);
  return [u0, u1, v0, v1];
}

/** The corners of a region, in the order handles are numbered: (u0,v0), (u1,v0), (u1,v1), (u0,v1). */
export function regionCorners(r: Region): UV[] {
  return [
    [r[0], r[2]],
    [r[1], r[2]],
    [r[1], r[3]],
    [r[0], r[3]],
  ];
}

/** The region with corner `corner` (regionCorners' numbering) dragged to `to`; the opposite
 * corner stays. */
export function resizeRegion(r: Region, corner: number, to: UV): Region {
  const opposite = regionCorners(r)[(corner + 2) % 4];
  return regionFromCorners(opposite, to);
}

/** The region moved by the drag from `from` to `to`, kept whole inside the patch. */
export function moveRegion(r: Region, from: UV, to: UV): Region {
  const w = r[1] - r[0], h = r[3] - r[2];
  const u0 = Math.min(1 - w, Math.max(0, r[0] + to[0] - from[0]));
  const v0 = Math.min(1 - h, Math.max(0, r[2] + to[1] - from[1]));
  return [round(u0), round(u0 + w), round(v0), round(v0 + h)];
}

/** Points round a region's border, `perSide` a side, counter-clockwise from (u0, v0): what
 * the surface view draws (each side's last point is the next side's first). */
export function regionOutline(r: Region, perSide: number): UV[] {
  const corners = regionCorners(r);
  const out: UV[] = [];
  for (let s = 0; s < 4; ++s) {
    const a = corners[s], b = corners[(s + 1) % 4];
    for (let i = 0; i < perSide; ++i) {
      const t = i / perSide;
      out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
    }
  }
  return out;
}

/** How far a frame force moves its region's middle, per coordinate: the particular solution
 * −f0 / (π² (a1/Lu² + a2/Lv²)) of the seed's PDE at the region's centre (Lu, Lv its sides in
 * u and v; docs/vertex-frames.md). A coordinate where a1/Lu² + a2/Lv² is 0 has no solution:
 * NaN there (the server refuses such a force). */
export function forceDisplacement(f0: readonly number[], a1: readonly number[], a2: readonly number[], region: Region): [number, number, number] {
  const lu = region[1] - region[0], lv = region[3] - region[2];
  return [0, 1, 2].map((c) => {
    const stiffness = Math.PI * Math.PI * (a1[c] / (lu * lu) + a2[c] / (lv * lv));
    return f0[c] === 0 ? 0 : stiffness === 0 ? NaN : -f0[c] / stiffness;
  }) as [number, number, number];
}

/** The force's effect in words, for the panel: how far and which way its region's middle
 * moves. */
export function forceEffectText(d: readonly number[]): string {
  if (d.some((x) => Number.isNaN(x))) return 'no solution: a1/Lu² + a2/Lv² is 0 in a coordinate where f0 is not';
  const length = Math.hypot(d[0], d[1], d[2]);
  if (length === 0) return 'f0 is 0: the region does not move';
  const fmt = (x: number) => (Math.abs(x) < 1e-12 ? '0' : x.toPrecision(3).replace(/\.?0+$/, '').replace(/\.?0+e/, 'e'));
  const main = [0, 1, 2].reduce((a, c) => (Math.abs(d[c]) > Math.abs(d[a]) ? c : a), 0);
  return `its middle moves by (${d.map(fmt).join(', ')}), ${fmt(length)} long, mostly toward ${d[main] < 0 ? '−' : '+'}${'xyz'[main]}`;
}

/** The shared force over exactly the frames `frames` (sorted), if the model has one: the one
 * the panel's f0 sliders set while those frames are selected. */
export function sharedForceOf(model: Model | null, frames: readonly number[]): SharedForce | undefined {
  const key = frames.join(',');
  return model?.forces?.find((f) => [...f.frames].sort((a, b) => a - b).join(',') === key);
}

/** How far a shared force moves the middle of each of its frames' patches: it acts on each
 * frame whole (region [0, 1]², with that frame's a1 and a2), as a frame force there. */
export function sharedDisplacements(model: Model, force: SharedForce): { frame: number; d: [number, number, number] }[] {
  return force.frames.map((k) => {
    const frame = model.frames[k];
    return { frame: k, d: forceDisplacement(force.f0, frame.a1 ?? [1, 1, 1], frame.a2 ?? [1, 1, 1], [0, 1, 0, 1]) };
  });
}

/** A shared force's effect in words: the move of each frame's middle when all its frames
 * take the same, else that of the frame it moves most. */
export function sharedEffectText(model: Model, force: SharedForce): string {
  const moves = sharedDisplacements(model, force);
  const length = (d: readonly number[]) => Math.hypot(d[0], d[1], d[2]);
  const most = moves.reduce((a, b) => (length(b.d) > length(a.d) ? b : a), moves[0]);
  const same = moves.every((m) => m.d.every((x, c) => x === most.d[c]));
  const text = forceEffectText(most.d);
  return same ? `on each of its ${moves.length} frames ${text}` : `most on frame ${most.frame}: ${text}`;
}
