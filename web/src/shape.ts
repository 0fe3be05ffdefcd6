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
  | { op: 'move-curve-points'; curve: CurveRef; points: number[]; positions: Vec3[]; group?: string }
  | { op: 'transform-curve'; curve: CurveRef; translate?: Vec3; rotate?: { axis: Vec3; degrees: number }; scale?: number; center?: Vec3 }
  | { op: 'set-operator'; operator?: 'ugail' | 'fu'; N?: number; a?: number; modes?: number; remainder?: boolean; group?: string }
  | { op: 'set-spine'; spine: SpineEdit[]; group?: string }
  | { op: 'add-section'; index: number }
  | { op: 'remove-section'; index: number }
  | { op: 'move-control-points'; points: [number, number][]; positions: Vec3[]; group?: string };

/** A point a user may drag: a curve's point, a given control point of a net, a spine point. */
export type Handle =
  | { kind: 'curve'; curve: CurveRef; point: number; p: Vec3 }
  | { kind: 'control'; i: number; j: number; p: Vec3 }
  | { kind: 'spine'; index: number; p: Vec3 };

/** A curve the panel lists: its reference, a label, and the centre turns and scales pivot on. */
export interface CurveEntry {
  ref: CurveRef;
  label: string;
  centre: Vec3;
}

// The model files' shapes, as far as the page reads them (docs/model-format.md).
type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

const SIDES = ['uMin', 'uMax', 'vMin', 'vMax'];
const CLOSED = ['start', 'end'];
const SECONDS = ['uMinSecond', 'vMinSecond'];

/** The point lists of a model's curves, by reference (positions only: a derivative
 * condition's or a tangent's vectors are not handles), and Fourier curves' centres. */
function curveLists(model: Json): { ref: CurveRef; label: string; points: Vec3[] | null; a0?: Vec3 }[] {
  const out: { ref: CurveRef; label: string; points: Vec3[] | null; a0?: Vec3 }[] = [];
  const spectralCurve = (ref: number, label: string, curve: Json) =>
    out.push({ ref, label, points: curve.points ?? null, a0: curve.fourier?.a0 });
  if (model.type === 'spectral')
    (model.conditions as Json[]).forEach((c, i) => {
      const d = c.derivative ?? 0;
      spectralCurve(i, `condition ${i}${c.u !== undefined ? ` (u = ${c.u})` : ''}${d ? `, ∂${d}u` : ''}`, c.curve);
      if (d) out[out.length - 1].points = null; // vectors, not points
    });
  else if (model.type === 'cross-sections') (model.curves as Json[]).forEach((c, i) => spectralCurve(i, `section ${i}`, c));
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
    named(model.blend, SIDES, 'bspline');
    named(model['closed-blend'], CLOSED, 'bspline');
  }
  return out;
}

/** The curves the panel lists, with their centres (the mean of their points, or a0). */
export function curveEntries(model: Json): CurveEntry[] {
  return curveLists(model).map(({ ref, label, points, a0 }) => {
    let centre: Vec3 = a0 ?? [0, 0, 0];
    if (points?.length) {
      centre = [0, 1, 2].map((c) => points.reduce((s, p) => s + p[c], 0) / points.length) as Vec3;
    }
    return { ref, label, centre };
  });
}

/** Every handle of a model: its curves' points, a net's given control points (rows 0, 1,
 * n_u; columns 0, 1, n_v), a spectral model's spine points (from the server's view). */
export function shapeHandles(model: Json, view: ModelView | null): Handle[] {
  const out: Handle[] = [];
  for (const { ref, points } of curveLists(model))
    points?.forEach((p, point) => out.push({ kind: 'curve', curve: ref, point, p }));
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

/** The edit that puts handle `h` at `target` (absolute: a drag's later steps replace its
 * earlier ones). `spine` is the model's spine list when the drag began. */
export function dragEdit(h: Handle, target: Vec3, spine: SpineEdit[], view: ModelView | null): ShapeEdit {
  if (h.kind === 'curve') return { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [target] };
  if (h.kind === 'control') return { op: 'move-control-points', points: [[h.i, h.j]], positions: [target] };
  const handles = view?.spineHandles;
  if (!handles) throw new Error('this model has no spine to drag');
  return { op: 'set-spine', spine: spineWith(spine, handles.u, handles.points, h.index, target) };
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
