// The shape editor of spectral, cross-section and B-spline PDE models: handles in the frame
// view for the points of their curves, the given control points of a net and a spectral
// model's spine points; a drag is one undo group of absolute edits (the surface previewed
// as vertex drags are); the panel's curve transforms, sections and operator. Every change is
// a server edit (shape.ts makes them), so it is checked, undoable, journalled and saved.
import * as THREE from 'three';
import type { Edit, Vec3 } from './api';
import { $, readNumber } from './dom';
import type { NumberRule } from './input';
import { curveEntries, dragEdit, operatorOf, shapeHandles } from './shape';
import type { Handle, ShapeEdit, SpineEdit } from './shape';
import type { Studio } from './studio';

/** Presses that move less than this many pixels are clicks. */
const CLICK_PIXELS = 5;
/** A handle is under the pointer within this many pixels of its centre. */
const PICK_PIXELS = 10;
/** Handle diameters in CSS pixels: curve points, control points, spine points. */
const HANDLE_PIXELS = 7;
const COLOURS = { curve: 0x3d5a80, control: 0x2e7d32, spine: 0xee6c4d, picked: 0xffb300 };

type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

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

  let handles: Handle[] = [];
  let picked: Handle | null = null;
  let drag: { handle: Handle; index: number; pointer: number; spine: SpineEdit[]; moved: boolean; x: number; y: number } | null = null;

  const shape = (): Json | null => {
    const s = store.state;
    return s.viewOnly && s.shape ? (s.shape as Json) : null;
  };

  const sameRef = (a: Handle, b: Handle) =>
    a.kind === b.kind &&
    (a.kind === 'curve' ? b.kind === 'curve' && a.curve === b.curve && a.point === b.point
      : a.kind === 'control' ? b.kind === 'control' && a.i === b.i && a.j === b.j
      : b.kind === 'spine' && a.index === b.index);

  function draw(): void {
    const model = shape();
    handles = model ? shapeHandles(model, store.state.view) : [];
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
    frameView.invalidate();
  }

  /** The handle nearest a client point (within PICK_PIXELS), front-most first. */
  function handleAt(x: number, y: number): number | null {
    let best: number | null = null;
    let score = Infinity;
    handles.forEach((h, i) => {
      const s = frameView.toClient(new THREE.Vector3(...h.p));
      const d = Math.hypot(s.x - x, s.y - y);
      if (!s.visible || d > PICK_PIXELS) return;
      if (d + s.z * 1e-3 < score) (score = d + s.z * 1e-3), (best = i);
    });
    return best;
  }

  function describe(h: Handle | null): string {
    if (!h) return 'none';
    if (h.kind === 'curve') return `${typeof h.curve === 'number' ? `curve ${h.curve}` : h.curve}, point ${h.point}`;
    if (h.kind === 'control') return `P[${h.i}][${h.j}]`;
    return `spine point ${h.index} (u = ${store.state.view?.spineHandles?.u[h.index]})`;
  }

  /** Marks handle `h` (null: none); `choose`: its curve becomes the panel's (a click on it). */
  function pick(h: Handle | null, choose = false): void {
    picked = h;
    $('shape-handle').textContent = describe(h);
    if (choose && h?.kind === 'curve') $<HTMLSelectElement>('curve-select').value = String(h.curve);
    draw();
  }
  // A curve chosen in the list: the handle picked before is no longer the subject.
  $('curve-select').addEventListener('change', () => pick(null));

  // ------------------------------------------------------------------ dragging handles
  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button !== 0 || !shape()) return;
    const index = handleAt(ev.clientX, ev.clientY);
    if (index === null) return;
    frameView.controls.enabled = false; // this listener runs before the controls'
    const handle = handles[index];
    drag = { handle, index, pointer: ev.pointerId, spine: structuredClone(shape()!.spine ?? []), moved: false, x: ev.clientX, y: ev.clientY };
    canvas.setPointerCapture(ev.pointerId);
    pick(handle, true);
    ev.preventDefault();
    ev.stopImmediatePropagation();
  });

  canvas.addEventListener('pointermove', (ev) => {
    if (!drag || ev.pointerId !== drag.pointer) {
      if (ev.buttons === 0 && shape()) {
        const cursor = handleAt(ev.clientX, ev.clientY) !== null ? 'grab' : '';
        if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
      }
      return;
    }
    if (!drag.moved) {
      if (Math.hypot(ev.clientX - drag.x, ev.clientY - drag.y) < CLICK_PIXELS) return;
      drag.moved = true;
      studio.beginGesture('shape-drag');
    }
    const { handle, index, spine } = drag;
    const target = frameView.dragTarget(handle.p, ev.clientX, ev.clientY);
    if (!target) return;
    moveHandle(index, target);
    const view = store.state.view;
    pump.push(() => send({ ...dragEdit(handle, target, spine, view) }));
  });

  async function endDrag(ev: PointerEvent): Promise<void> {
    if (!drag || ev.pointerId !== drag.pointer) return;
    const moved = drag.moved;
    drag = null;
    frameView.controls.enabled = true;
    if (!moved) return;
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
    const model = shape();
    const value = $<HTMLSelectElement>('curve-select').value;
    const entry = model ? curveEntries(model).find((e) => String(e.ref) === value) : undefined;
    if (!entry) throw new Error('Curve: choose a curve first');
    return entry;
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
      return { op: 'transform-curve', curve: entry.ref, rotate: { axis, degrees: numberOf('curve-rotate-degrees') }, center: entry.centre };
    }),
  );
  $('curve-scale').addEventListener('click', () =>
    once('scaled the curve', () => {
      const entry = chosenCurve();
      return { op: 'transform-curve', curve: entry.ref, scale: numberOf('curve-scale-factor', { min: 0, nonZero: true }), center: entry.centre };
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

  function fillPanel(): void {
    const model = shape();
    $('shape-tools').hidden = !model;
    if (!model) return;
    const select = $<HTMLSelectElement>('curve-select');
    const was = select.value;
    select.replaceChildren(
      ...curveEntries(model).map((e) => {
        const option = document.createElement('option');
        option.value = String(e.ref);
        option.textContent = e.label;
        return option;
      }),
    );
    if ([...select.options].some((o) => o.value === was)) select.value = was;
    $('curve-tools').hidden = select.options.length === 0; // a net has points, no curves
    $('section-tools').hidden = model.type !== 'cross-sections';
    const spectral = model.type === 'spectral';
    $('operator-tools').hidden = !spectral && model.type !== 'cross-sections';
    if (model.type === 'bspline-pde') return;
    const op = operatorOf(model);
    $('operator-kind-label').hidden = $('operator-n-label').hidden = !spectral;
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
    if (picked && !shapeHandles(shape() ?? {}, store.state.view).some((h) => sameRef(h, picked!))) picked = null;
    fillPanel();
    pick(picked);
  });

  if (navigator.webdriver || new URLSearchParams(location.search).has('test'))
    window.__shape = {
      /** The client point of every handle, with what it is. */
      handles: () =>
        handles.map((h) => {
          const s = frameView.toClient(new THREE.Vector3(...h.p));
          return { ...h, x: s.x, y: s.y, visible: s.visible };
        }),
    };
}
