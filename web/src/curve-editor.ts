// The shape editor of spectral, cross-section and B-spline PDE models: handles in the frame
// view for the points of their curves, the tips of their tangents, the given control points
// of a net and a spectral model's spine points, and a centre mark per curve (click: choose
// the curve; drag: move the whole curve, Fourier curves too; the gizmo (G) on the chosen
// curve: its arrows on the centre, its rings and boxes on the panel's pivot); a drag is one
// undo group of absolute edits (the surface previewed as vertex drags are); the panel's curve
// transforms (Shift+R, Shift+S, about the pivot), sections and operator.
// Every change is a server edit (shape.ts makes them), so it is checked, undoable,
// journalled and saved.
import * as THREE from 'three';
import type { Edit, ModelState, Vec3 } from './api';
import { $, readNumber } from './dom';
import type { NumberRule } from './input';
import { gizmoSubjects, pivotChoice, pivotPlaces } from './gizmo';
import { axisAngleOf, scaledAlong, turnedBy } from './orientation';
import { singlePivot } from './selection-transform';
import { curveMoveEdit, dragEdit, shapePanels } from './shape';
import type { CurveEntry, CurveRef, Handle, ShapeEdit, ShapeHandles } from './shape';
import type { Studio } from './studio';

/** Presses that move less than this many pixels are clicks. */
const CLICK_PIXELS = 5;
/** A handle is under the pointer within this many pixels of its centre. */
const PICK_PIXELS = 10;
/** Handle diameters in CSS pixels: curve points, control points, spine points, tangent tips. */
const HANDLE_PIXELS = 7;
/** The curves' centre marks: larger than the points, so a curve is grabbed whole there. */
const CENTRE_PIXELS = 12;
const COLOURS = { curve: 0x3d5a80, control: 0x2e7d32, spine: 0xee6c4d, tangent: 0x6a994e, picked: 0xffb300, centre: 0x7b2cbf };

declare global {
  interface Window {
    __shape: unknown;
  }
}

const send = (edit: ShapeEdit): Edit => edit;

export function mountCurveEditor(studio: Studio): void {
  const { store, frameView, pump } = studio;
  const canvas = frameView.renderer.domElement;
  const material = new THREE.PointsMaterial({ size: HANDLE_PIXELS, sizeAttenuation: false, vertexColors: true });
  const points = new THREE.Points(new THREE.BufferGeometry(), material);
  points.frustumCulled = false;
  points.renderOrder = 4;
  frameView.scene.add(points);
  // The centre of every curve that holds positions (not vectors): drawn over the lines.
  const centreMarks = new THREE.Points(
    new THREE.BufferGeometry(),
    new THREE.PointsMaterial({ size: CENTRE_PIXELS, sizeAttenuation: false, vertexColors: true, depthTest: false }),
  );
  centreMarks.frustumCulled = false;
  centreMarks.renderOrder = 5;
  frameView.scene.add(centreMarks);
  // A tangent: a line from its base point to its tip handle.
  const tangentLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: COLOURS.tangent }));
  tangentLines.frustumCulled = false;
  frameView.scene.add(tangentLines);

  let handles: Handle[] = [];
  /** Per handle, its line among tangentLines' (the tangents' lines are in handle order), -1
   * for a handle that is no tangent tip. */
  let tangentLine: number[] = [];
  let centres: CurveEntry[] = [];
  let picked: Handle | null = null;
  /** Whether the chosen curve was taken whole (its centre mark clicked): the panel says so. */
  let whole = false;
  /** A drag: of a handle (`index` in handles), or of a curve's centre mark (`curve`: the
   * curve's point handles and centre follow by the same offset). */
  let drag:
    | { handle: Handle; index: number; pointer: number; moved: boolean; x: number; y: number; curve?: undefined }
    | { curve: CurveMove; pointer: number; moved: boolean; x: number; y: number }
    | null = null;

  /** The server's handles of the model (null: a model with editable parts, or none yet). */
  const served = (): ShapeHandles | null => (store.state.hasEditableParts ? null : store.state.handles);

  const sameRef = (a: Handle, b: Handle) =>
    a.kind === b.kind &&
    (a.kind === 'curve' || a.kind === 'tangent' ? (b.kind === 'curve' || b.kind === 'tangent') && a.curve === b.curve && a.point === b.point
      : a.kind === 'control' ? b.kind === 'control' && a.i === b.i && a.j === b.j
      : b.kind === 'spine' && a.index === b.index);

  /** The curve chosen in the panel's list (null: none, or no curves). */
  const chosen = (): CurveEntry | null => {
    const value = $<HTMLSelectElement>('curve-select').value;
    return served()?.curves.find((e) => String(e.ref) === value) ?? null;
  };

  function draw(): void {
    const server = served();
    centres = server ? server.curves.filter((e) => !e.vectors) : [];
    const choice = chosen();
    const cxyz = new Float32Array(3 * centres.length);
    const crgb = new Float32Array(3 * centres.length);
    const cc = new THREE.Color();
    centres.forEach((e, i) => {
      cxyz.set(e.centre, 3 * i);
      cc.setHex(choice && choice.ref === e.ref ? COLOURS.picked : COLOURS.centre);
      crgb.set([cc.r, cc.g, cc.b], 3 * i);
    });
    centreMarks.geometry.setAttribute('position', new THREE.BufferAttribute(cxyz, 3));
    centreMarks.geometry.setAttribute('color', new THREE.BufferAttribute(crgb, 3));
    centreMarks.visible = centres.length > 0;
    handles = server ? server.points : [];
    const tangents = handles.filter((h) => h.kind === 'tangent');
    let line = 0;
    tangentLine = handles.map((h) => (h.kind === 'tangent' ? line++ : -1));
    tangentLines.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(tangents.flatMap((h) => [...h.base, ...h.p])), 3));
    tangentLines.visible = tangents.length > 0;
    const xyz = new Float32Array(3 * handles.length);
    const rgb = new Float32Array(3 * handles.length);
    const c = new THREE.Color();
    handles.forEach((h, i) => {
      xyz.set(h.p, 3 * i);
      c.setHex(picked && sameRef(h, picked) ? COLOURS.picked : COLOURS[h.kind]);
      rgb.set([c.r, c.g, c.b], 3 * i);
    });
    points.geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    points.geometry.setAttribute('color', new THREE.BufferAttribute(rgb, 3));
    points.visible = handles.length > 0;
    frameView.invalidate();
  }

  function moveHandle(index: number, p: Vec3): void {
    const a = points.geometry.getAttribute('position') as THREE.BufferAttribute;
    a.setXYZ(index, p[0], p[1], p[2]);
    a.needsUpdate = true;
    const k = tangentLine[index] ?? -1;
    if (k >= 0) {
      // Its line's tip.
      const l = tangentLines.geometry.getAttribute('position') as THREE.BufferAttribute;
      l.setXYZ(2 * k + 1, p[0], p[1], p[2]);
      l.needsUpdate = true;
    }
    frameView.invalidate();
  }

  /** The handle nearest a client point (within PICK_PIXELS), front-most first: an index in
   * `handles`, or { centre } for a curve's centre mark. */
  function handleAt(x: number, y: number): number | { centre: number } | null {
    let best: number | { centre: number } | null = null;
    let score = Infinity;
    const consider = (p: Vec3, what: number | { centre: number }, bias = 0) => {
      const s = frameView.toClient(new THREE.Vector3(...p));
      const d = Math.hypot(s.x - x, s.y - y);
      if (!s.visible || d > PICK_PIXELS) return;
      if (d + s.z * 1e-3 - bias < score) (score = d + s.z * 1e-3 - bias), (best = what);
    };
    handles.forEach((h, i) => consider(h.p, i));
    // A centre mark is drawn over everything (and larger): on a point it covers, it wins.
    centres.forEach((e, centre) => consider(e.centre, { centre }, CENTRE_PIXELS / 4));
    return best;
  }

  /** A whole curve being moved, turned or scaled (a centre drag or the gizmo): its point
   * handles and centre mark where they started; each step puts them where the step's map takes
   * them and sends the curve's edit from the drag's start (one absolute edit). */
  interface CurveMove {
    ref: CurveRef;
    centre: Vec3;
    mark: number;
    moved: { index: number; from: Vec3 }[];
  }
  function beginCurveMove(entry: CurveEntry): CurveMove {
    studio.beginGesture('curve-move');
    const moved = handles.flatMap((h, index) => (h.kind === 'curve' && h.curve === entry.ref ? [{ index, from: h.p }] : []));
    return { ref: entry.ref, centre: entry.centre, mark: centres.findIndex((e) => e.ref === entry.ref), moved };
  }
  function stepCurve(m: CurveMove, at: (p: Vec3) => Vec3, edit: ShapeEdit): void {
    for (const { index, from } of m.moved) moveHandle(index, at(from));
    if (m.mark >= 0) {
      const a = centreMarks.geometry.getAttribute('position') as THREE.BufferAttribute;
      a.setXYZ(m.mark, ...at(m.centre));
      a.needsUpdate = true;
    }
    frameView.invalidate();
    pump.push(() => send(edit));
  }
  function stepCurveMove(m: CurveMove, d: Vec3): void {
    stepCurve(m, (p) => [p[0] + d[0], p[1] + d[1], p[2] + d[2]], curveMoveEdit(m.ref, d));
  }
  /** The point the chosen curve turns and scales about: the panel's pivot where it names one
   * place (the cursor, the origin, the handle picked on the curve as the active point), else
   * the curve's centre. */
  function curvePivot(entry: CurveEntry): Vec3 {
    const active = picked?.kind === 'curve' && picked.curve === entry.ref ? picked.p : null;
    return singlePivot(pivotChoice(), pivotPlaces(studio, active)) ?? entry.centre;
  }
  async function endCurveMove(): Promise<void> {
    await studio.endGesture();
    await studio.reloadModel(); // the curve, its centre and handles as the server has them
  }

  function describe(h: Handle | null): string {
    if (!h) {
      const entry = whole ? chosen() : null;
      return entry ? `${entry.label}, whole` : 'none';
    }
    if (h.kind === 'curve') return `${typeof h.curve === 'number' ? `curve ${h.curve}` : h.curve}, point ${h.point}`;
    if (h.kind === 'tangent') return `${typeof h.curve === 'number' ? `curve ${h.curve}` : h.curve}, ${h.mean ? 'mean tangent (a0)' : `tangent ${h.point}`}`;
    if (h.kind === 'control') return `P[${h.i}][${h.j}]`;
    return `spine point ${h.index} (u = ${h.u})`;
  }

  /** Marks handle `h` (null: none); `choose`: its curve becomes the panel's (a click on it). */
  function pick(h: Handle | null, choose = false): void {
    picked = h;
    if (h) whole = false;
    $('shape-handle').textContent = describe(h);
    if (choose && (h?.kind === 'curve' || h?.kind === 'tangent')) chooseCurve(h.curve);
    draw();
    gizmoSubjects.changed?.(); // on a picked control point
  }
  /** Makes `ref` the panel's curve (the one the keys, the gizmo and the buttons act on). */
  function chooseCurve(ref: CurveRef): void {
    $<HTMLSelectElement>('curve-select').value = String(ref);
    gizmoSubjects.changed?.();
  }
  // A curve chosen in the list: the handle picked before is no longer the subject.
  $('curve-select').addEventListener('change', () => {
    whole = false;
    pick(null);
    gizmoSubjects.changed?.();
  });

  // ------------------------------------------------------------------ dragging handles
  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button !== 0 || !served()) return;
    const index = handleAt(ev.clientX, ev.clientY);
    if (index === null) return;
    frameView.controls.enabled = false; // this listener runs before the controls'
    if (typeof index === 'object') {
      // A centre mark: the curve is chosen; a drag moves it whole.
      const entry = centres[index.centre];
      chooseCurve(entry.ref);
      whole = true;
      pick(null);
      drag = { curve: { ref: entry.ref, centre: entry.centre, mark: index.centre, moved: [] }, pointer: ev.pointerId, moved: false, x: ev.clientX, y: ev.clientY };
      canvas.setPointerCapture(ev.pointerId);
      ev.preventDefault();
      ev.stopImmediatePropagation();
      return;
    }
    const handle = handles[index];
    drag = { handle, index, pointer: ev.pointerId, moved: false, x: ev.clientX, y: ev.clientY };
    canvas.setPointerCapture(ev.pointerId);
    pick(handle, true);
    ev.preventDefault();
    ev.stopImmediatePropagation();
  });

  canvas.addEventListener('pointermove', (ev) => {
    if (!drag || ev.pointerId !== drag.pointer) {
      if (ev.buttons === 0 && served()) {
        const cursor = handleAt(ev.clientX, ev.clientY) !== null ? 'grab' : '';
        if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
      }
      return;
    }
    if (!drag.moved) {
      if (Math.hypot(ev.clientX - drag.x, ev.clientY - drag.y) < CLICK_PIXELS) return;
      drag.moved = true;
      if (drag.curve) {
        const entry = centres[drag.curve.mark];
        drag.curve = beginCurveMove(entry);
      } else {
        studio.beginGesture('shape-drag');
      }
    }
    if (drag.curve) {
      const m = drag.curve;
      const target = frameView.dragTarget(m.centre, ev.clientX, ev.clientY);
      if (target) stepCurveMove(m, [target[0] - m.centre[0], target[1] - m.centre[1], target[2] - m.centre[2]]);
      return;
    }
    const { handle, index } = drag;
    const target = frameView.dragTarget(handle.p, ev.clientX, ev.clientY);
    if (!target) return;
    moveHandle(index, target);
    const server = served();
    if (server) pump.push(() => send({ ...dragEdit(handle, target, server) }));
  });

  async function endDrag(ev: PointerEvent): Promise<void> {
    if (!drag || ev.pointerId !== drag.pointer) return;
    const { moved, curve } = drag;
    drag = null;
    frameView.controls.enabled = true;
    if (!moved) return;
    if (curve) return endCurveMove();
    await studio.endGesture();
    await studio.reloadModel(); // the curves, spine and handles as the server now has them
  }
  canvas.addEventListener('pointerup', (ev) => void endDrag(ev));
  canvas.addEventListener('pointercancel', (ev) => void endDrag(ev));

  // ------------------------------------------------------------------ the panel
  /** One edit that is its own undo step, then the model and surface again. */
  const once = (what: string, make: () => ShapeEdit) =>
    void studio.run(async () => {
      const edit = make();
      await pump.once(what, () => send(edit));
      if (store.state.error) throw new Error(store.state.error); // refused (the pump reloaded)
      studio.say(what);
      await studio.reloadAll();
    });

  function numberOf(id: string, rule: NumberRule = {}): number {
    let message = '';
    const value = readNumber($<HTMLInputElement>(id), rule, (m) => (message = m));
    if (value === null) throw new Error(message);
    return value;
  }

  const chosenCurve = () => {
    const entry = chosen();
    if (!entry) throw new Error('Curve: choose a curve first (click its centre mark, or pick it in the list)');
    return entry;
  };
  // The gizmo (G) on the chosen curve: its arrows on the curve's centre (a curve of vectors has
  // none: a translation leaves vectors as they are), its rings (transform-curve: a turn about
  // the pivot, Fourier curves and vectors too) and boxes (the curve's points scaled along an
  // axis: move-curve-points; a curve without points cannot scale along one axis) on the pivot.
  let gizmoMove: (CurveMove & { pivot: Vec3 }) | null = null;
  // A given control point of a net picked (a net has no curves): the gizmo moves, turns and
  // scales it alone about the pivot (move-control-points, absolute).
  const pickedControl = () => (served() && picked?.kind === 'control' ? picked : null);
  const controlPivot = (h: Handle) => singlePivot(pivotChoice(), pivotPlaces(studio, h.p)) ?? h.p;
  let gizmoPoint: { h: Extract<Handle, { kind: 'control' }>; index: number; pivot: Vec3 } | null = null;
  const stepPoint = (at: (p: Vec3) => Vec3) => {
    const { h, index } = gizmoPoint!;
    const target = at(h.p);
    moveHandle(index, target);
    pump.push(() => send({ op: 'move-control-points', points: [[h.i, h.j]], positions: [target] }));
  };
  gizmoSubjects.shape = {
    centre: () => {
      const control = pickedControl();
      if (control) return control.p;
      const entry = chosen();
      return entry && !entry.vectors ? entry.centre : null;
    },
    pivot: () => {
      const control = pickedControl();
      if (control) return controlPivot(control);
      const entry = chosen();
      return entry ? curvePivot(entry) : null;
    },
    begin: (kind) => {
      const control = pickedControl();
      if (control) {
        gizmoPoint = { h: control, index: handles.findIndex((h) => sameRef(h, control)), pivot: controlPivot(control) };
        studio.beginGesture('control-point');
        return true;
      }
      const entry = chosen();
      if (!entry) return false;
      if (kind === 'scale' && (entry.vectors || !handles.some((h) => h.kind === 'curve' && h.curve === entry.ref))) {
        studio.say(`the boxes scale a curve of points along an axis; ${entry.label} has none (Fourier coefficients or vectors): Shift+S scales it by one factor`);
        return false;
      }
      gizmoMove = { ...beginCurveMove(entry), pivot: curvePivot(entry) };
      return true;
    },
    move: (d) => {
      if (gizmoPoint) stepPoint((p) => [p[0] + d[0], p[1] + d[1], p[2] + d[2]]);
      else if (gizmoMove) stepCurveMove(gizmoMove, d);
    },
    turn: (q) => {
      if (gizmoPoint) stepPoint((p) => turnedBy(p, gizmoPoint!.pivot, q));
      if (!gizmoMove) return;
      const { pivot, ref } = gizmoMove;
      const rotate = axisAngleOf(q);
      stepCurve(gizmoMove, (p) => turnedBy(p, pivot, q), { op: 'transform-curve', curve: ref, rotate, center: pivot, from: 'group-start' });
    },
    scale: (f, basis) => {
      if (gizmoPoint) stepPoint((p) => scaledAlong(p, gizmoPoint!.pivot, basis, f));
      if (!gizmoMove) return;
      const { pivot, ref, moved } = gizmoMove;
      const at = (p: Vec3) => scaledAlong(p, pivot, basis, f);
      const points = moved.map(({ index }) => (handles[index] as Extract<Handle, { kind: 'curve' }>).point);
      stepCurve(gizmoMove, at, { op: 'move-curve-points', curve: ref, points, positions: moved.map(({ from }) => at(from)) });
    },
    end: async () => {
      if (!gizmoMove && !gizmoPoint) return;
      gizmoMove = gizmoPoint = null;
      await endCurveMove();
    },
  };

  $('curve-move').addEventListener('click', () =>
    once('moved the curve', () => ({
      op: 'transform-curve',
      curve: chosenCurve().ref,
      translate: [numberOf('curve-move-x'), numberOf('curve-move-y'), numberOf('curve-move-z')],
    })),
  );
  $('curve-rotate').addEventListener('click', () =>
    once('turned the curve', () => {
      const axis: Vec3 = [0, 0, 0];
      axis[['x', 'y', 'z'].indexOf($<HTMLSelectElement>('curve-rotate-axis').value)] = 1;
      const entry = chosenCurve();
      return { op: 'transform-curve', curve: entry.ref, rotate: { axis, degrees: numberOf('curve-rotate-degrees') }, center: curvePivot(entry) };
    }),
  );
  $('curve-scale').addEventListener('click', () =>
    once('scaled the curve', () => {
      const entry = chosenCurve();
      return { op: 'transform-curve', curve: entry.ref, scale: numberOf('curve-scale-factor', { min: 0, nonZero: true }), center: curvePivot(entry) };
    }),
  );
  $('add-section').addEventListener('click', () =>
    once('added a section', () => ({ op: 'add-section', index: Number(chosenCurve().ref) + 1 })),
  );
  $('remove-section').addEventListener('click', () =>
    once('removed a section', () => ({ op: 'remove-section', index: Number(chosenCurve().ref) })),
  );

  // The operator: each change one edit; the slider of a is one gesture (one undo step).
  const setOperator = (fields: Partial<Extract<ShapeEdit, { op: 'set-operator' }>>) =>
    once('changed the operator', () => ({ op: 'set-operator', ...fields }));
  $('operator-kind').addEventListener('change', () =>
    setOperator({ operator: $<HTMLSelectElement>('operator-kind').value as 'ugail' | 'fu' }),
  );
  $('operator-n').addEventListener('change', () => setOperator({ N: numberOf('operator-n', { min: 1 }) }));
  $('operator-modes').addEventListener('change', () =>
    setOperator({ modes: numberOf('operator-modes', { min: 0 }) }),
  );
  $('operator-remainder').addEventListener('change', () =>
    setOperator({ remainder: $<HTMLInputElement>('operator-remainder').checked }),
  );
  $('operator-a').addEventListener('change', () => setOperator({ a: numberOf('operator-a') }));
  const slider = $<HTMLInputElement>('operator-a-slider');
  slider.addEventListener('pointerdown', () => studio.beginGesture('operator-a'));
  slider.addEventListener('input', () => {
    const a = Number(slider.value);
    $<HTMLInputElement>('operator-a').value = String(a);
    if (!pump.active) studio.beginGesture('operator-a'); // keys move the slider too
    pump.push(() => send({ op: 'set-operator', a }));
  });
  slider.addEventListener('change', () => void studio.endGesture().then(() => studio.reloadModel()));

  $('use-global-chain').addEventListener('click', () =>
    once('the global chain', () => ({ op: 'set-operator', method: 'global' })),
  );

  function fillPanel(): void {
    const settings = store.state.hasEditableParts ? null : store.state.settings;
    $('shape-tools').hidden = !settings;
    if (!settings) return;
    const select = $<HTMLSelectElement>('curve-select');
    const was = select.value;
    select.replaceChildren(
      ...(served()?.curves ?? []).map((e) => {
        const option = document.createElement('option');
        option.value = String(e.ref);
        option.textContent = e.label;
        return option;
      }),
    );
    if ([...select.options].some((o) => o.value === was)) select.value = was;
    $('curve-tools').hidden = select.options.length === 0; // a net has points, no curves
    const panels = shapePanels(settings);
    $('section-tools').hidden = !panels.sections;
    // Told before the drag, not after: the seed's marching chains and ill-conditioned patches.
    const advice = (store.state.status as ModelState | null)?.dragAdvice ?? '';
    $('drag-advice').hidden = !advice;
    $('drag-advice-text').textContent = advice;
    $('use-global-chain').hidden = !panels.globalChain;
    const op = panels.operator;
    $('operator-tools').hidden = !op;
    if (!op) return;
    $('operator-kind-label').hidden = !panels.operatorKind;
    $('operator-n-label').hidden = !panels.operatorN;
    if (op.operator) $<HTMLSelectElement>('operator-kind').value = op.operator;
    $<HTMLInputElement>('operator-n').value = String(op.N ?? '');
    $<HTMLInputElement>('operator-modes').value = String(op.modes);
    $<HTMLInputElement>('operator-remainder').checked = op.remainder;
    if (!pump.active) {
      $<HTMLInputElement>('operator-a').value = String(op.a);
      slider.value = String(op.a);
    }
  }

  store.subscribe(['model'], () => {
    if (picked && !(served()?.points ?? []).some((h) => sameRef(h, picked!))) picked = null;
    fillPanel();
    pick(picked);
    gizmoSubjects.changed?.();
  });

  if (navigator.webdriver || new URLSearchParams(location.search).has('test'))
    window.__shape = {
      /** The client point of every handle, with what it is. */
      handles: () =>
        handles.map((h) => {
          const s = frameView.toClient(new THREE.Vector3(...h.p));
          return { ...h, x: s.x, y: s.y, visible: s.visible };
        }),
      /** The client point of every curve's centre mark, with its curve. */
      centres: () =>
        centres.map((e) => {
          const s = frameView.toClient(new THREE.Vector3(...e.centre));
          return { curve: e.ref, p: e.centre, x: s.x, y: s.y, visible: s.visible };
        }),
    };
}
