// The shape edits of spectral, cross-section and B-spline PDE models as the page makes them:
// which points of a model file are handles, the edit a handle's drag sends, the curves the
// panel lists. No DOM here (web/test/shape.test.ts checks it); curve-editor.ts draws and drags.
import type { ModelView, Vec3 } from './api';

/** A spine edit as the model file's "spine" field holds it (docs/model-format.md). */
export interface SpineEdit {
  u: number[];
  moved: Vec3[];
}

/** A curve of a model: a condition's or section's index, or a B-spline curve's name. */
export type CurveRef = number | string;

/** The shape edits the server takes (include/pdesurf/edit_io.hpp: parseShapeEdit). */
export type ShapeEdit =
  | { op: 'move-curve-points'; curve: CurveRef; points: number[]; positions: Vec3[]; falloff?: number; group?: string }
  | { op: 'transform-curve'; curve: CurveRef; translate?: Vec3; rotate?: { axis: Vec3; degrees: number }; scale?: number; center?: Vec3; from?: 'group-start'; group?: string }
  | { op: 'set-fourier'; curve: CurveRef; a0?: Vec3; a?: Vec3[]; b?: Vec3[]; group?: string }
  | { op: 'set-operator'; operator?: 'ugail' | 'fu'; N?: number; a?: number; modes?: number; remainder?: boolean; method?: 'global' | 'c2' | 'shared-curves'; group?: string }
  | { op: 'set-spine'; spine: SpineEdit[]; group?: string }
  | { op: 'add-section'; index: number }
  | { op: 'remove-section'; index: number }
  | { op: 'move-control-points'; points: [number, number][]; positions: Vec3[]; group?: string };

/** A point a user may drag: a curve's point, a given control point of a net, a spine point,
 * the tip of a tangent (a derivative condition's or a tangent row's vector, drawn from its
 * base point on the position curve: p = base + TANGENT_DRAW × vector). */
export type Handle =
  | { kind: 'curve'; curve: CurveRef; point: number; p: Vec3 }
  | { kind: 'control'; i: number; j: number; p: Vec3 }
  | { kind: 'spine'; index: number; p: Vec3 }
  | { kind: 'tangent'; curve: CurveRef; point: number; p: Vec3; base: Vec3; mean?: boolean };

/** Tangent tips are drawn at this fraction of their vector from the base point: a tangent is
 * a derivative (a length per unit of u), often longer than the model; a quarter keeps its
 * tip near the surface and its direction plain. */
export const TANGENT_DRAW = 0.25;

/** A curve the panel lists: its reference, a label, the centre turns and scales pivot on, and
 * whether it holds vectors (a derivative condition, a tangent row: no translation, turns and
 * scales through its linear part). */
export interface CurveEntry {
  ref: CurveRef;
  label: string;
  centre: Vec3;
  vectors: boolean;
}

// The model files' shapes, as far as the page reads them (docs/model-format.md).
type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

const SIDES = ['uMin', 'uMax', 'vMin', 'vMax'];
const CLOSED = ['start', 'end'];
const SECONDS = ['uMinSecond', 'vMinSecond'];

/** A model curve as the page reads it: its points when they are positions (null for Fourier
 * curves and vectors), a Fourier curve's a0, and a vector curve's vectors with the base point
 * each is drawn from (when the page can place them). */
interface CurveList {
  ref: CurveRef;
  label: string;
  points: Vec3[] | null;
  a0?: Vec3;
  vectors?: { at: Vec3[]; base: Vec3[]; mean?: boolean } | null;
}

/** The mean of `points`. */
function meanOf(points: Vec3[]): Vec3 {
  return [0, 1, 2].map((c) => points.reduce((s, p) => s + p[c], 0) / points.length) as Vec3;
}

/** Cumulative chord length of `points`, from 0 to 1 (uniform when they all coincide). */
function chordParameters(points: Vec3[]): number[] {
  const t = [0];
  for (let k = 1; k < points.length; ++k) {
    const [a, b] = [points[k - 1], points[k]];
    t.push(t[k - 1] + Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]));
  }
  const total = t[t.length - 1];
  return total > 0 ? t.map((x) => x / total) : t.map((_, k) => k / Math.max(points.length - 1, 1));
}

/** The polyline through `points` at parameters `t` (increasing, 0 to 1), at `s`. */
function alongPolyline(points: Vec3[], t: number[], s: number): Vec3 {
  let k = 1;
  while (k < points.length - 1 && t[k] < s) ++k;
  const span = t[k] - t[k - 1];
  const w = span > 0 ? Math.min(Math.max((s - t[k - 1]) / span, 0), 1) : 0;
  return [0, 1, 2].map((c) => points[k - 1][c] + w * (points[k][c] - points[k - 1][c])) as Vec3;
}

/** The point lists of a model's curves, by reference, with what their points are (positions,
 * Fourier a0, or vectors and where they are drawn from). */
function curveLists(model: Json): CurveList[] {
  const out: CurveList[] = [];
  const spectralCurve = (ref: number, label: string, curve: Json) =>
    out.push({ ref, label, points: curve.points ?? null, a0: curve.fourier?.a0 });
  if (model.type === 'spectral') {
    const conditions = model.conditions as Json[];
    conditions.forEach((c, i) => {
      const d = c.derivative ?? 0;
      spectralCurve(i, `condition ${i}${c.u !== undefined ? ` (u = ${c.u})` : ''}${d ? `, ∂${d}u` : ''}`, c.curve);
      if (!d) return;
      const entry = out[out.length - 1];
      entry.points = null; // vectors, not points
      entry.vectors = null;
      if (d !== 1) return; // a tangent has tips; a higher derivative turns and scales whole
      // Its tips drawn from the points of the position condition at the same u, when that
      // is given as as many points (the j-th vector belongs to the j-th point); a Fourier
      // curve's a0 (its mean over v) from that condition's centre (a0, or its points' mean).
      const at = c.curve.points as Vec3[] | undefined;
      const position = conditions.find((p) => (p.derivative ?? 0) === 0 && p.u === c.u)?.curve as Json | undefined;
      const positionPoints = position?.points as Vec3[] | undefined;
      if (at && positionPoints && positionPoints.length === at.length) entry.vectors = { at, base: positionPoints };
      const mean = c.curve.fourier ? ((c.curve.fourier.a0 ?? [0, 0, 0]) as Vec3) : null;
      const centre = position?.fourier ? ((position.fourier.a0 ?? [0, 0, 0]) as Vec3) : positionPoints?.length ? meanOf(positionPoints) : null;
      if (mean && centre) entry.vectors = { at: [mean], base: [centre], mean: true };
    });
  } else if (model.type === 'cross-sections') (model.curves as Json[]).forEach((c, i) => spectralCurve(i, `section ${i}`, c));
  else if (model.type === 'bspline-pde') {
    const named = (part: Json | undefined, names: string[], key?: string) => {
      for (const name of names) {
        const c = part?.[name];
        if (!c) continue;
        const points = key ? c[key] : (c.bspline ?? c.points);
        if (Array.isArray(points)) out.push({ ref: name, label: name, points });
      }
    };
    named(model.boundary, SIDES);
    named(model.boundary, SECONDS, 'points');
    // A tangent row (x_u along u = 0, x_v along v = 0): vectors drawn from the side they
    // leave, at their parameters (given, else uniform; a B-spline's control vectors at
    // uniform parameters) on that side (its samples' t, else chord length).
    SECONDS.forEach((name, s) => {
      const tangent = model.boundary?.[name]?.tangent as Json | undefined;
      const at = (tangent?.points ?? tangent?.bspline) as Vec3[] | undefined;
      const side = model.boundary?.[s === 0 ? 'uMin' : 'vMin'] as Json | undefined;
      const sidePoints = (side?.points ?? side?.bspline) as Vec3[] | undefined;
      if (!at || !sidePoints) return;
      const t: number[] = tangent!.t ?? at.map((_, k) => k / Math.max(at.length - 1, 1));
      const sideT: number[] = side!.t ?? chordParameters(sidePoints);
      out.push({ ref: name, label: `${name} (tangent)`, points: null, vectors: { at, base: t.map((x) => alongPolyline(sidePoints, sideT, x)) } });
    });
    named(model.blend, SIDES, 'bspline');
    named(model['closed-blend'], CLOSED, 'bspline');
  }
  return out;
}

/** The curves the panel lists, with their centres (the mean of their points, or a0). */
export function curveEntries(model: Json): CurveEntry[] {
  return curveLists(model).map(({ ref, label, points, a0, vectors }) => {
    let centre: Vec3 = a0 ?? [0, 0, 0];
    if (points?.length) centre = meanOf(points);
    return { ref, label, centre, vectors: vectors !== undefined };
  });
}

/** Every handle of a model: its curves' points, a net's given control points (rows 0, 1,
 * n_u; columns 0, 1, n_v), a spectral model's spine points (from the server's view). */
export function shapeHandles(model: Json, view: ModelView | null): Handle[] {
  const out: Handle[] = [];
  for (const { ref, points, vectors } of curveLists(model)) {
    points?.forEach((p, point) => out.push({ kind: 'curve', curve: ref, point, p }));
    vectors?.at.forEach((v, point) => {
      const base = vectors.base[point];
      const p = [0, 1, 2].map((c) => base[c] + TANGENT_DRAW * v[c]) as Vec3;
      out.push({ kind: 'tangent', curve: ref, point, base, p, ...(vectors.mean ? { mean: true } : {}) });
    });
  }
  if (model.type === 'bspline-pde' && Array.isArray(model.net)) {
    const net = model.net as (Vec3 | null)[][];
    const nu = net.length - 1;
    net.forEach((row, i) => {
      const nv = row.length - 1;
      row.forEach((p, j) => {
        if (p && (i <= 1 || i === nu || j <= 1 || j === nv)) out.push({ kind: 'control', i, j, p });
      });
    });
  }
  view?.spineHandles?.points.forEach((p, index) => out.push({ kind: 'spine', index, p }));
  return out;
}

function sameNumbers(a: number[], b: number[]): boolean {
  return a.length === b.length && a.every((x, i) => x === b[i]);
}

/** The spine list after dragging spine handle `k` (at u[k], of the handles at `u` with their
 * points `points`) to `target`: the other handles held where they are. A last edit on the same
 * u takes the new point (the file keeps one edit per set of handles); else one is added. */
export function spineWith(spine: SpineEdit[], u: number[], points: Vec3[], k: number, target: Vec3): SpineEdit[] {
  const last = spine[spine.length - 1];
  if (last && sameNumbers(last.u, u))
    return [...spine.slice(0, -1), { u, moved: last.moved.map((p, i) => (i === k ? target : p)) }];
  return [...spine, { u, moved: points.map((p, i) => (i === k ? target : p)) }];
}

/** A point of a closed curve (a section, a spectral condition: the curves named by number)
 * drags the curve round it too, in a compact bump this fraction of the curve's length each
 * side (kStudioFalloff in include/pdesurf/session.hpp): the section stays smooth and the edit
 * local. B-spline curves (named) are control polygons, local already. */
export const CLOSED_CURVE_FALLOFF = 0.125;

/** The edit that puts handle `h` at `target` (absolute: a drag's later steps replace its
 * earlier ones). `spine` is the model's spine list when the drag began. */
export function dragEdit(h: Handle, target: Vec3, spine: SpineEdit[], view: ModelView | null): ShapeEdit {
  if (h.kind === 'curve')
    return typeof h.curve === 'number'
      ? { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [target], falloff: CLOSED_CURVE_FALLOFF }
      : { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [target] };
  if (h.kind === 'tangent') {
    const vector = [0, 1, 2].map((c) => (target[c] - h.base[c]) / TANGENT_DRAW) as Vec3;
    if (h.mean) return { op: 'set-fourier', curve: h.curve, a0: vector };
    return { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [vector] };
  }
  if (h.kind === 'control') return { op: 'move-control-points', points: [[h.i, h.j]], positions: [target] };
  const handles = view?.spineHandles;
  if (!handles) throw new Error('this model has no spine to drag');
  return { op: 'set-spine', spine: spineWith(spine, handles.u, handles.points, h.index, target) };
}

/** One step of a drag of a whole curve: the curve moved by `d` from where it was when the drag
 * began (the server applies it to the model before the drag's group: absolute, so a step
 * replaces the last and the curve ends exactly `d` away; a Fourier curve's a0 takes `d`, its
 * modes stay). */
export function curveMoveEdit(curve: CurveRef, d: Vec3): ShapeEdit {
  return { op: 'transform-curve', curve, translate: d, from: 'group-start' };
}

/** The operator settings a spectral model or a chain has, with the files' defaults. */
export function operatorOf(model: Json): { operator: 'ugail' | 'fu' | null; N: number | null; a: number; modes: number; remainder: boolean } {
  const modes = model.modes ?? 6;
  const remainder = model.remainder ?? true;
  if (model.type === 'cross-sections') return { operator: null, N: null, a: model.a ?? 1, modes, remainder };
  const fu = model.operator === 'fu';
  const N = fu ? 3 : (model.N ?? 2);
  return { operator: fu ? 'fu' : 'ugail', N, a: model.a ?? (fu ? 1 : N), modes, remainder };
}
