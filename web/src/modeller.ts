// The modeller: the toolbar's Model group (new model, extrude, add frame, delete, split,
// weld, flip: each one structure edit of the server's session, one undo step), the new-model
// dialog, the selection's typed offset, scale and turn (one move-vertices edit each), the move
// gizmo (gizmo.ts), forces drawn on the surface (forces-tool.ts), and in the surface view:
// picking frames (the triangle in front under the pointer, its frame from GET
// /api/patch-ids) and box-selecting the vertices seen (none hidden behind the surface).
import * as THREE from 'three';
import { api } from './api';
import type { Vec3 } from './api';
import { $, makeButton, readNumber } from './dom';
import { mountForcesTool } from './forces-tool';
import type { ForcesTool } from './forces-tool';
import { mountGizmo, selectionPivots, selectionVertices } from './gizmo';
import type { Gizmo } from './gizmo';
import { modelBox } from './viewport';
import { scaledAbout } from './selection-transform';
import { fromBasis, isGlobal, rotatedAboutAxis } from './orientation';
import type { Studio } from './studio';
import { addFrameEdit, coincidentWith, extrudeEdit, framesEdit, mirrorEdit, selectAll, selectInverse, selectLinked, selectStrip, splitEdit, toggled, toggledInStack, weldEdit } from './structure';
import type { Made } from './structure';
import { SurfacePicker } from './surface-pick';
import { mirrorPartners, symmetricMove, symmetryPlane } from './symmetry';
import { studioBasis } from './drag';
import type { DragTool } from './drag';

/** The modeller's tools, for the browser tests (test-hooks.ts). */
export const modellerTools: { gizmo?: Gizmo; forces?: ForcesTool } = {};

/** Presses that move less than this many pixels are clicks (not orbits). */
const CLICK_PIXELS = 5;
/** A click on the surface view picks a vertex seen within this many pixels of it (the
 * selection dots are 9 px across; farther, the click picks the patch under it). */
const SURFACE_VERTEX_PICK_PIXELS = 8;

export interface ModellerActions {
  newModel(): void;
  extrude(): void;
  addFrame(): void;
  deleteFrames(): void;
  split(parts: '4' | 'u' | 'v'): void;
  weld(): void;
  flip(): void;
  /** Copies the selected frames across the panel's symmetry plane. */
  mirror(): void;
  toggleGizmo(): void;
  /** Shows the gizmo with its next kind of handles (move, rotate, scale). */
  cycleGizmo(): void;
  scaleSelection(): void;
  rotateSelection(): void;
  toggleDrawForce(): void;
  /** Select all, the inverse of the selection, everything linked to it, or the strips of
   * frames through it along u (loop) or v (ring). */
  select(how: 'all' | 'inverse' | 'linked' | 'loop' | 'ring'): void;
}

/** The selection buttons: what each selects (ModellerActions.select), its label and title. */
const SELECTIONS = [
  ['all', 'All', 'Every frame and vertex (Ctrl+A)'],
  ['inverse', 'Invert', 'What is not selected (Ctrl+I)'],
  ['linked', 'Linked', 'Every frame joined to the selection, with its vertices (Ctrl+L)'],
  ['loop', 'Loop', 'The strip of frames through each selected frame across its u = 0 and u = 1 sides, round a tube too (Alt+L)'],
  ['ring', 'Ring', 'The strip of frames through each selected frame across its v = 0 and v = 1 sides (Alt+R)'],
] as const;


export function mountModeller(
  studio: Studio,
  mayLeave: () => Promise<boolean>,
  refreshFiles: () => Promise<void>,
  dragTool?: DragTool,
): ModellerActions {
  const { store, surfaceView } = studio;

  /** Sends a structure edit made from the selection (or says what to select). */
  const send = (make: () => Made) =>
    void studio.run(async () => {
      const model = store.state.model;
      if (!model) throw new Error(`${store.state.modelType} models have no editable parts: no structure edits`);
      const made = make();
      if ('problem' in made) throw new Error(made.problem);
      const status = await api.edit(made.edit);
      store.update(['status'], (s) => (s.status = status));
      await studio.reloadAll();
    });

  const actions: ModellerActions = {
    newModel: () => {
      const dialog = $<HTMLDialogElement>('new-dialog');
      if (!dialog.open) dialog.showModal();
    },
    extrude: () => send(() => extrudeEdit(store.state.model!, store.state.selectedVertices)),
    addFrame: () => send(() => addFrameEdit(store.state.selectedVertices)),
    deleteFrames: () => send(() => framesEdit('delete-frames', store.state.selectedFrames)),
    split: (parts) => send(() => splitEdit(store.state.selectedFrames, parts)),
    weld: () => send(() => weldEdit(store.state.model!, store.state.selectedVertices)),
    flip: () => send(() => framesEdit('flip-frames', store.state.selectedFrames)),
    mirror: () => send(() => mirrorEdit(store.state.selectedFrames, symmetryPlane($<HTMLSelectElement>('symmetry').value, store.state.model!.vertices))),
    // Set below, with the tools they drive.
    toggleGizmo: () => {},
    cycleGizmo: () => {},
    scaleSelection: () => {},
    rotateSelection: () => {},
    toggleDrawForce: () => {},
    // Queued as the toolbar's actions are: Ctrl+A pressed while an undo's reload is in flight
    // selects the frames of the model the undo restores, not those of the model it replaces.
    select: (how) =>
      void studio.run(async () => {
        const model = store.state.model;
        if (!model) return;
        const picked = { vertices: store.state.selectedVertices, frames: store.state.selectedFrames };
        const next =
          how === 'all'
            ? selectAll(model)
            : how === 'inverse'
              ? selectInverse(model, picked)
              : how === 'linked'
                ? selectLinked(model, picked)
                : selectStrip(model, picked, how === 'loop' ? 'u' : 'v');
        store.update(['selection', 'forces'], (s) => {
          s.selectedVertices = next.vertices;
          s.selectedVertex = next.vertices.length ? next.vertices[next.vertices.length - 1] : null;
          s.selectedFrames = next.frames;
          s.selectedForce = 0;
        });
        studio.say(`${next.vertices.length} vertices, ${next.frames.size} frames selected`);
      }),
  };
  $('select-buttons').append(...SELECTIONS.map(([how, label, title]) => makeButton(`select-${how}`, label, title, () => actions.select(how))));
  $('new-model').addEventListener('click', actions.newModel);
  $('extrude').addEventListener('click', actions.extrude);
  $('add-frame').addEventListener('click', actions.addFrame);
  $('delete-frames').addEventListener('click', actions.deleteFrames);
  $('split-4').addEventListener('click', () => actions.split('4'));
  $('split-u').addEventListener('click', () => actions.split('u'));
  $('split-v').addEventListener('click', () => actions.split('v'));
  $('weld').addEventListener('click', actions.weld);
  $('flip').addEventListener('click', actions.flip);
  $('mirror-frames').addEventListener('click', actions.mirror);
  store.subscribe(['model'], (state) => {
    for (const button of $('model-tools').querySelectorAll<HTMLButtonElement>('button:not([data-testid="new-model"])'))
      button.disabled = !state.model;
  });

  // The new-model dialog: written to a new file under the root, then opened.
  const dialog = $<HTMLDialogElement>('new-dialog');
  $('new-cancel').addEventListener('click', () => dialog.close());
  $('new-create').addEventListener('click', () =>
    void studio.run(async () => {
      const report = (message: string) => studio.showError(message);
      const u = readNumber($<HTMLInputElement>('new-u'), { label: 'u', min: 1, max: 64 }, report);
      const v = readNumber($<HTMLInputElement>('new-v'), { label: 'v', min: 1, max: 64 }, report);
      const size = readNumber($<HTMLInputElement>('new-size'), { label: 'size', min: 0, nonZero: true }, report);
      if (u === null || v === null || size === null) return;
      dialog.close();
      if (!(await mayLeave())) return;
      const kind = $<HTMLSelectElement>('new-kind').value as 'single' | 'grid' | 'tube';
      const path = $<HTMLInputElement>('new-path').value.trim();
      const made = await api.newModel({ path, kind, u, v, size });
      studio.say(`new model ${made.path}`);
      await studio.reloadAll(true);
      await refreshFiles();
    }),
  );

  /** Moves the selection's vertices to the places `place` gives them: one move-vertices edit. */
  const moveSelection = (what: string, place: (points: Vec3[]) => Vec3[] | null) =>
    void studio.run(async () => {
      const model = store.state.model;
      const vertices = selectionVertices(studio);
      if (!model || !vertices.length) throw new Error(`${what}: select vertices or frames first`);
      const from = vertices.map((v) => model.vertices[v]);
      const to = place(from);
      if (!to) return;
      // With symmetry on, the partners across the plane follow mirrored (symmetry.ts).
      const plane = symmetryPlane($<HTMLSelectElement>('symmetry').value, model.vertices);
      const edit = plane ? symmetricMove(plane, mirrorPartners(model.vertices, vertices, from, plane), vertices, to) : { vertices, positions: to };
      const status = await api.edit({ op: 'move-vertices', ...edit });
      store.update(['status'], (s) => (s.status = status));
      await studio.reloadAll();
    });
  const numberIn = (id: string, rule: Parameters<typeof readNumber>[1] = {}) =>
    readNumber($<HTMLInputElement>(id), rule, (m) => studio.showError(m));

  // The selection moved by a typed offset, scaled or turned about its pivot; the offset and
  // the turn's axis along the panel's orientation (global: x, y, z as they are).
  $('offset-apply').addEventListener('click', () =>
    moveSelection('Move', (points) => {
      const d = ['x', 'y', 'z'].map((axis) => numberIn(`offset-${axis}`, { label: `d${axis}` }));
      if (d.some((x) => x === null)) return null;
      const basis = studioBasis(studio, selectionVertices(studio));
      const by = isGlobal(basis) ? (d as Vec3) : fromBasis(d as Vec3, basis);
      return points.map((p) => p.map((x, i) => x + by[i]) as Vec3);
    }),
  );
  /** Each selected vertex's pivot, as the panel's *pivot* says (selection-transform.ts). */
  const pivots = (points: Vec3[]) => selectionPivots(studio, selectionVertices(studio), points);
  actions.scaleSelection = () =>
    moveSelection('Scale', (points) => {
      const factor = numberIn('selection-scale', { label: 'scale factor', min: 0, nonZero: true });
      return factor === null ? null : pivots(points).map((c, i) => scaledAbout([points[i]], c, factor)[0]);
    });
  actions.rotateSelection = () =>
    moveSelection('Rotate', (points) => {
      const degrees = numberIn('selection-degrees', { label: 'degrees' });
      const axis = studioBasis(studio, selectionVertices(studio))['xyz'.indexOf($<HTMLSelectElement>('selection-axis').value)];
      return degrees === null ? null : pivots(points).map((c, i) => rotatedAboutAxis([points[i]], c, axis, degrees)[0]);
    });
  $('selection-scale-apply').addEventListener('click', actions.scaleSelection);
  $('selection-rotate-apply').addEventListener('click', actions.rotateSelection);
  store.subscribe(['selection', 'model'], (state) => {
    const n = state.selectedVertices.length || (state.selectedVertex !== null ? 1 : 0);
    $('vertex-selection').textContent = n === 0 ? 'no vertices' : n === 1 ? '1 vertex' : `${n} vertices`;
  });

  // A click on a vertex seen on the surface selects it (shift: adds or removes it, ctrl:
  // removes it), as in the frame view; elsewhere on the surface the frame of the patch in
  // front (shift or ctrl: adds or removes it); shift+drag (ctrl+drag) selects (removes) the
  // vertices seen in a box.
  const picker = new SurfacePicker(studio);
  const canvas = surfaceView.renderer.domElement;
  let press: { x: number; y: number } | null = null;
  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button === 0) press = { x: ev.clientX, y: ev.clientY };
  });
  canvas.addEventListener('pointerup', (ev) => {
    const start = press;
    press = null;
    const mesh = store.state.mesh;
    if (!start || !store.state.model || !mesh || Math.hypot(ev.clientX - start.x, ev.clientY - start.y) >= CLICK_PIXELS) return;
    const model = store.state.model;
    const size = modelBox(model).getSize(new THREE.Vector3()).length();
    const vertex = picker.vertexAt(model.vertices, ev.clientX, ev.clientY, SURFACE_VERTEX_PICK_PIXELS, size);
    if (vertex !== null) {
      const mode = ev.shiftKey ? 'toggle' : ev.ctrlKey || ev.metaKey ? 'remove' : null;
      const next = mode ? toggledInStack(store.state.selectedVertices, vertex, coincidentWith(model, vertex), mode) : [vertex];
      store.update(['selection'], (s) => {
        s.selectedVertices = next;
        s.selectedVertex = next.length ? next[next.length - 1] : null;
      });
      return;
    }
    const hit = picker.hit(ev.clientX, ev.clientY);
    const adding = ev.shiftKey || ev.ctrlKey || ev.metaKey;
    void studio.run(async () => {
      const frame = hit ? await picker.frameOf(hit.triangle) : null;
      store.update(['selection', 'forces'], (s) => {
        if (frame === null) {
          if (!adding) s.selectedFrames = new Set();
          return;
        }
        const next = adding ? new Set(s.selectedFrames) : new Set<number>();
        if (adding && next.has(frame)) next.delete(frame);
        else next.add(frame);
        s.selectedFrames = next;
        s.selectedForce = 0;
      });
    });
  });

  // A press on a vertex seen on the surface (within the pick radius, not hidden behind it)
  // drags it as its handle in the frame view does, in the plane facing this view's camera:
  // taken in the capture phase of the view's container, before the orbit controls.
  if (dragTool) {
    const container = surfaceView.container;
    container.addEventListener(
      'pointerdown',
      (ev) => {
        const model = store.state.model;
        if (ev.button !== 0 || !model || ev.shiftKey || ev.ctrlKey || ev.metaKey) return;
        const size = modelBox(model).getSize(new THREE.Vector3()).length();
        const vertex = picker.vertexAt(model.vertices, ev.clientX, ev.clientY, SURFACE_VERTEX_PICK_PIXELS, size);
        if (vertex === null) return;
        dragTool.begin(surfaceView, vertex, ev);
        canvas.setPointerCapture(ev.pointerId);
        press = null; // a drag, not a click on the patch
      },
      true,
    );
    canvas.addEventListener('pointermove', (ev) => dragTool.move(ev));
    const end = (ev: PointerEvent) => void dragTool.end(ev);
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
  }

  // The box: taken in the capture phase of the view's container, before the orbit controls.
  let box: { x: number; y: number; pointer: number; remove: boolean; div: HTMLDivElement } | null = null;
  const container = surfaceView.container;
  container.addEventListener(
    'pointerdown',
    (ev) => {
      if (ev.button !== 0 || !store.state.model || !(ev.shiftKey || ev.ctrlKey || ev.metaKey)) return;
      surfaceView.controls.enabled = false; // no orbit; the click still selects a frame
      const div = document.createElement('div');
      div.className = 'select-box';
      div.dataset.testid = 'surface-select-box';
      document.body.append(div);
      box = { x: ev.clientX, y: ev.clientY, pointer: ev.pointerId, remove: !ev.shiftKey, div };
    },
    true,
  );
  container.addEventListener('pointermove', (ev) => {
    if (!box || ev.pointerId !== box.pointer) return;
    Object.assign(box.div.style, {
      left: `${Math.min(box.x, ev.clientX)}px`,
      top: `${Math.min(box.y, ev.clientY)}px`,
      width: `${Math.abs(ev.clientX - box.x)}px`,
      height: `${Math.abs(ev.clientY - box.y)}px`,
    });
  });
  const endBox = (ev: PointerEvent) => {
    if (!box || ev.pointerId !== box.pointer) return;
    const b = box;
    box = null;
    b.div.remove();
    surfaceView.controls.enabled = true;
    const model = store.state.model;
    if (!model || Math.hypot(ev.clientX - b.x, ev.clientY - b.y) < CLICK_PIXELS) return;
    const size = modelBox(model).getSize(new THREE.Vector3()).length();
    const [left, right] = [Math.min(b.x, ev.clientX), Math.max(b.x, ev.clientX)];
    const [top, bottom] = [Math.min(b.y, ev.clientY), Math.max(b.y, ev.clientY)];
    picker.refresh();
    let next = [...store.state.selectedVertices];
    model.vertices.forEach((v, i) => {
      const s = surfaceView.toClient(new THREE.Vector3(...v));
      if (s.x < left || s.x > right || s.y < top || s.y > bottom || !picker.seen(v, size)) return;
      next = toggled(next, i, b.remove ? 'remove' : 'add');
    });
    store.update(['selection'], (s) => {
      s.selectedVertices = next;
      s.selectedVertex = next.length ? next[next.length - 1] : null;
    });
  };
  container.addEventListener('pointerup', endBox);
  container.addEventListener('pointercancel', endBox);

  // The selected vertices, drawn over the surface too.
  const dots = new THREE.Points(
    new THREE.BufferGeometry(),
    new THREE.PointsMaterial({ color: 0xee6c4d, size: 9, sizeAttenuation: false, depthTest: false }),
  );
  dots.renderOrder = 5;
  dots.frustumCulled = false;
  surfaceView.scene.add(dots);
  store.subscribe(['model', 'selection', 'vertex'], (state, topics) => {
    const model = state.model;
    const picked = model ? state.selectedVertices.filter((v) => v < model.vertices.length) : [];
    dots.geometry.setAttribute('position', new THREE.Float32BufferAttribute(picked.flatMap((v) => model!.vertices[v]), 3));
    // A drag's moved vertex alone ('vertex') waits for the surface of that edit, which draws
    // the view anyway: a draw now would hold the page while the edit's answer comes in, and
    // would show the dot ahead of its surface.
    if (topics.has('model') || topics.has('selection')) surfaceView.invalidate();
  });

  const gizmo = mountGizmo(studio);
  const forces = mountForcesTool(studio, picker);
  actions.toggleGizmo = gizmo.toggle;
  actions.cycleGizmo = gizmo.cycle;
  actions.toggleDrawForce = forces.toggleDraw;
  modellerTools.gizmo = gizmo;
  modellerTools.forces = forces;
  return actions;
}
