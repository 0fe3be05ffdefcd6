// The modeller: the toolbar's Model group (new model, extrude, add frame, delete, split,
// weld, flip: each one structure edit of the server's session, one undo step), the new-model
// dialog, the selection's typed offset, and picking frames on the surface (the triangle in
// front under the pointer, its frame from GET /api/patch-ids).
import { api } from './api';
import type { Vec3 } from './api';
import { $, readNumber } from './dom';
import type { Studio } from './studio';
import {
  addFrameEdit,
  extrudeEdit,
  frameOfTriangle,
  framesEdit,
  splitEdit,
  weldEdit,
} from './structure';
import type { Made } from './structure';

/** Presses that move less than this many pixels are clicks (not orbits). */
const CLICK_PIXELS = 5;

export interface ModellerActions {
  newModel(): void;
  extrude(): void;
  addFrame(): void;
  deleteFrames(): void;
  split(parts: '4' | 'u' | 'v'): void;
  weld(): void;
  flip(): void;
}

export function mountModeller(studio: Studio, mayLeave: () => Promise<boolean>, refreshFiles: () => Promise<void>): ModellerActions {
  const { store, surfaceView } = studio;

  /** Sends a structure edit made from the selection (or says what to select). */
  const send = (make: () => Made) =>
    void studio.run(async () => {
      const model = store.state.model;
      if (!model) throw new Error(`${store.state.viewOnly} models are view-only: no structure edits`);
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
  };
  $('new-model').addEventListener('click', actions.newModel);
  $('extrude').addEventListener('click', actions.extrude);
  $('add-frame').addEventListener('click', actions.addFrame);
  $('delete-frames').addEventListener('click', actions.deleteFrames);
  $('split-4').addEventListener('click', () => actions.split('4'));
  $('split-u').addEventListener('click', () => actions.split('u'));
  $('split-v').addEventListener('click', () => actions.split('v'));
  $('weld').addEventListener('click', actions.weld);
  $('flip').addEventListener('click', actions.flip);
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

  // The selection moved by a typed offset: its vertices, else the selected frames' vertices.
  const selectionVertices = (): number[] => {
    const s = store.state;
    if (s.selectedVertices.length) return [...s.selectedVertices];
    if (s.selectedVertex !== null) return [s.selectedVertex];
    const all = new Set<number>();
    for (const f of s.selectedFrames) for (const v of s.model?.frames[f]?.vertices ?? []) all.add(v);
    return [...all].sort((a, b) => a - b);
  };
  $('offset-apply').addEventListener('click', () =>
    void studio.run(async () => {
      const model = store.state.model;
      const vertices = selectionVertices();
      if (!model || !vertices.length) throw new Error('Move: select vertices or frames first');
      const d: number[] = [];
      for (const axis of ['x', 'y', 'z']) {
        const value = readNumber($<HTMLInputElement>(`offset-${axis}`), { label: `d${axis}` }, (m) => studio.showError(m));
        if (value === null) return;
        d.push(value);
      }
      const positions = vertices.map((v) => model.vertices[v].map((x, i) => x + d[i]) as Vec3);
      const status = await api.edit({ op: 'move-vertices', vertices, positions });
      store.update(['status'], (s) => (s.status = status));
      await studio.reloadAll();
    }),
  );
  store.subscribe(['selection', 'model'], (state) => {
    const n = state.selectedVertices.length || (state.selectedVertex !== null ? 1 : 0);
    $('vertex-selection').textContent = n === 0 ? 'no vertices' : n === 1 ? '1 vertex' : `${n} vertices`;
  });

  // A click on the surface selects the frame of the patch in front (shift or ctrl: adds or
  // removes it). The triangles' frames come from the server once per mesh layout.
  const canvas = surfaceView.renderer.domElement;
  let ids: { key: string; ids: Uint32Array } | null = null;
  let press: { x: number; y: number } | null = null;
  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button === 0) press = { x: ev.clientX, y: ev.clientY };
  });
  canvas.addEventListener('pointerup', (ev) => {
    const start = press;
    press = null;
    const mesh = store.state.mesh;
    if (!start || !store.state.model || !mesh || Math.hypot(ev.clientX - start.x, ev.clientY - start.y) >= CLICK_PIXELS) return;
    const triangle = surfaceView.triangleAt(ev.clientX, ev.clientY);
    const adding = ev.shiftKey || ev.ctrlKey || ev.metaKey;
    void studio.run(async () => {
      let frame: number | null = null;
      if (triangle !== null) {
        // The layout depends on the frames and the resolution alone.
        const key = `${mesh.resolution}/${mesh.triangleCount}/${store.state.model!.frames.map((f) => f.vertices.join(',')).join(';')}`;
        if (ids?.key !== key) ids = { key, ids: (await api.patchIds(mesh.resolution)).ids };
        frame = frameOfTriangle(ids.ids, triangle);
      }
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
  return actions;
}
