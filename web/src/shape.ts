// The shape edits of spectral, cross-section and B-spline PDE models as the page makes them:
// the edit a drag of one of the server's handles sends, and which panels show. What they read
// is the server's (GET /api/model's "handles" and "settings"), never the model file. No DOM
// here (web/test/shape.test.ts checks it); curve-editor.ts draws and drags.
import type { OperatorSettings, ShapeSettings, Vec3 } from './api';

/** A curve of a model: a condition's or section's index, or a B-spline curve's name. */
export type CurveRef = number | string;

/** The shape edits the page sends (include/pdesurf/edit_io.hpp: parseShapeEdit). */
export type ShapeEdit =
  | { op: 'move-curve-points'; curve: CurveRef; points: number[]; positions: Vec3[]; falloff?: number; group?: string }
  | { op: 'transform-curve'; curve: CurveRef; translate?: Vec3; rotate?: { axis: Vec3; degrees: number }; scale?: number; center?: Vec3; from?: 'group-start'; group?: string }
  | { op: 'set-fourier'; curve: CurveRef; a0?: Vec3; a?: Vec3[]; b?: Vec3[]; group?: string }
  | { op: 'set-operator'; operator?: 'ugail' | 'fu'; N?: number; a?: number; modes?: number; remainder?: boolean; method?: 'global' | 'c2' | 'shared-curves'; group?: string }
  | { op: 'move-spine-point'; index: number; position: Vec3; group?: string }
  | { op: 'add-section'; index: number }
  | { op: 'remove-section'; index: number }
  | { op: 'move-control-points'; points: [number, number][]; positions: Vec3[]; group?: string };

/** A point a user may drag, as the server's handles list it (GET /api/model's "handles", the
 * model's method's SurfaceMethod::handles): a curve's point, a given control point of a net, a
 * spine point (at its u), the tip of a tangent (a derivative condition's or a tangent row's
 * vector, drawn from its base point on the position curve: p = base + tangentDraw × vector). */
export type Handle =
  | { kind: 'curve'; curve: CurveRef; point: number; p: Vec3 }
  | { kind: 'control'; i: number; j: number; p: Vec3 }
  | { kind: 'spine'; index: number; u: number; p: Vec3 }
  | { kind: 'tangent'; curve: CurveRef; point: number; p: Vec3; base: Vec3; mean?: boolean };

/** A curve the panel lists: its reference, a label, the centre turns and scales pivot on, and
 * whether it holds vectors (a derivative condition, a tangent row: no translation, turns and
 * scales through its linear part). */
export interface CurveEntry {
  ref: CurveRef;
  label: string;
  centre: Vec3;
  vectors: boolean;
}

/** What the server says a model offers to drag: its handles, its curves and how far from its
 * base a tangent's tip is drawn (a fraction of its vector). */
export interface ShapeHandles {
  points: Handle[];
  curves: CurveEntry[];
  tangentDraw: number;
}

/** A point of a closed curve (a section, a spectral condition: the curves named by number)
 * drags the curve round it too, in a compact bump this fraction of the curve's length each
 * side (kStudioFalloff in include/pdesurf/session.hpp): the section stays smooth and the edit
 * local. B-spline curves (named) are control polygons, local already. */
export const CLOSED_CURVE_FALLOFF = 0.125;

/** The edit that puts handle `h` (of the model's `handles`) at `target` (absolute: a drag's
 * later steps replace its earlier ones; a spine point's the server applies to the model as the
 * drag began, the other spine handles held where they were). */
export function dragEdit(h: Handle, target: Vec3, handles: ShapeHandles): ShapeEdit {
  if (h.kind === 'curve')
    return typeof h.curve === 'number'
      ? { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [target], falloff: CLOSED_CURVE_FALLOFF }
      : { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [target] };
  if (h.kind === 'tangent') {
    const vector = [0, 1, 2].map((c) => (target[c] - h.base[c]) / handles.tangentDraw) as Vec3;
    if (h.mean) return { op: 'set-fourier', curve: h.curve, a0: vector };
    return { op: 'move-curve-points', curve: h.curve, points: [h.point], positions: [vector] };
  }
  if (h.kind === 'control') return { op: 'move-control-points', points: [[h.i, h.j]], positions: [target] };
  return { op: 'move-spine-point', index: h.index, position: target };
}

/** One step of a drag of a whole curve: the curve moved by `d` from where it was when the drag
 * began (the server applies it to the model before the drag's group: absolute, so a step
 * replaces the last and the curve ends exactly `d` away; a Fourier curve's a0 takes `d`, its
 * modes stay). */
export function curveMoveEdit(curve: CurveRef, d: Vec3): ShapeEdit {
  return { op: 'transform-curve', curve, translate: d, from: 'group-start' };
}

/** Which parts of the shape panel show for a model and the operator's values, from what the
 * server says it offers (GET /api/model's "settings"): sections when it takes add-section and
 * remove-section; the operator when it has one, its kind and N when it names them; the global
 * chain's button when a chain is solved another way. */
export interface ShapePanels {
  sections: boolean;
  operator: OperatorSettings | null;
  operatorKind: boolean;
  operatorN: boolean;
  globalChain: boolean;
}

export function shapePanels(settings: ShapeSettings): ShapePanels {
  const op = settings.operator ?? null;
  return {
    sections: settings.edits.includes('add-section') && settings.edits.includes('remove-section'),
    operator: op,
    operatorKind: op?.operator !== undefined,
    operatorN: op?.N !== undefined,
    globalChain: op?.method !== undefined && op.method !== 'global',
  };
}
