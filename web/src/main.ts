// The studio page: wires the two views, the panel and the toolbar to the server through
// api.ts. The server holds the model; the page keeps a copy that it updates as it sends
// edits (so a drag is smooth) and reloads after undo, redo, open and any refused edit.
import './style.css';
import { api, applyDelta, ApiError } from './api';
import type { Edit, FrameForce, MeshData, Model, ModelState, Region, SharedForce, Status, Transform, Vec3 } from './api';
import { FrameView, SurfaceView, modelBox, pointsBox } from './scene';

const $ = <T extends HTMLElement = HTMLElement>(id: string): T => {
  const el = document.querySelector<T>(`[data-testid="${id}"]`);
  if (!el) throw new Error(`missing element ${id}`);
  return el;
};

// ----------------------------------------------------------------------------------------
// State

interface State {
  path: string;
  model: Model | null;
  status: Status | null;
  selectedVertex: number | null;
  selectedFrames: Set<number>;
  /** The selected force of a single selected frame (index in its forces). */
  selectedForce: number;
  mesh: MeshData | null;
  meshStale: boolean;
  /** The type of a view-only model (spectral, cross-sections, bspline-pde), or '' for an editable one. */
  viewOnly: string;
  error: string;
  message: string;
}

const state: State = {
  path: '',
  model: null,
  status: null,
  selectedVertex: null,
  selectedFrames: new Set(),
  selectedForce: 0,
  mesh: null,
  meshStale: false,
  viewOnly: '',
  error: '',
  message: '',
};

const frameView = new FrameView($('frame-view'));
const surfaceView = new SurfaceView($('surface-view'));

// ----------------------------------------------------------------------------------------
// Status line and errors

function plural(n: number, word: string): string {
  return `${n} ${word}${n === 1 ? '' : 's'}`;
}

function showError(e: unknown): void {
  state.error = e instanceof ApiError ? e.message : e instanceof Error ? e.message : String(e);
  renderStatus();
}

function renderStatus(): void {
  const m = state.model;
  const parts: string[] = [];
  if (m) parts.push(plural(m.frames.length, 'frame'), plural(m.vertices.length, 'vertex').replace('vertexs', 'vertices'));
  if (state.status) parts.push(`rev ${state.status.revision}`, `undo ${state.status.undo}`, `redo ${state.status.redo}`);
  if (state.mesh) {
    parts.push(`solve ${state.mesh.solveMs.toFixed(2)} ms`, `tessellate ${state.mesh.tessellateMs.toFixed(2)} ms`);
    parts.push(`${plural(state.mesh.triangleCount, 'triangle')}`);
  }
  if (state.viewOnly) parts.push(`${state.viewOnly} model: view only (edit its file; Transform moves it)`);
  if (state.meshStale) parts.push('surface out of date (Create)');
  if (state.message) parts.push(state.message);
  $('status').textContent = parts.join(' · ');
  $('error').textContent = state.error;
  $('model-path').textContent = state.path;
  $('dirty').hidden = !state.status?.dirty;
  $<HTMLButtonElement>('undo').disabled = !state.status || state.status.undo === 0;
  $<HTMLButtonElement>('redo').disabled = !state.status || state.status.redo === 0;
  $('surface-view').classList.toggle('surface-stale', state.meshStale);
  $('c0-gap').textContent = state.mesh ? `C0 gap ${formatGap(state.mesh.c0Gap)}` : '';
}

function formatGap(gap: number): string {
  if (!Number.isFinite(gap)) return '?';
  return gap === 0 ? '0' : gap.toExponential(2);
}

// ----------------------------------------------------------------------------------------
// The mesh: one request in flight, the latest revision fetched after it

let meshBusy = false;
let meshDeltas = 0; // meshes that came as deltas (tests)
let meshAgain = false;

async function requestMesh(): Promise<void> {
  if (meshBusy) {
    meshAgain = true;
    return;
  }
  meshBusy = true;
  try {
    let whole = false; // after a delta that did not fit: ask for the whole mesh
    do {
      meshAgain = false;
      const resolution = Number($<HTMLSelectElement>('resolution').value);
      const base = !whole && state.mesh?.resolution === resolution ? state.mesh.id : undefined;
      whole = false;
      const answer = await api.mesh({ resolution, base });
      if (answer.kind === 'delta') {
        if (!state.mesh || !applyDelta(state.mesh, answer)) {
          whole = meshAgain = true;
          continue;
        }
        surfaceView.updateVertices(answer.runs);
        ++meshDeltas;
      } else {
        state.mesh = answer;
        surfaceView.setMesh(answer);
      }
      state.meshStale = false;
      renderStatus();
    } while (meshAgain);
  } catch (e) {
    showError(e);
  } finally {
    meshBusy = false;
  }
}

const live = () => $<HTMLInputElement>('live').checked;

function modelChanged(): void {
  if (live()) void requestMesh();
  else state.meshStale = true;
}

// ----------------------------------------------------------------------------------------
// Edits: one in flight; while it is, only the latest of the next ones is kept

let groupCounter = 0;

type Operation = { kind: 'edit'; group: string; make: () => Edit } | { kind: 'end-group' };

/** Sends edits one at a time, in order. A gesture (drag, slider) is a group: while an edit
 * is in flight, only the latest next edit of the group is kept; its end closes the group
 * (POST /api/end-group) after its last edit. */
class EditPump {
  private group = '';
  private queue: Operation[] = [];
  private busy = false;
  private waiters: (() => void)[] = [];

  /** Starts a gesture (ending one still open): its edits share one undo group. */
  begin(kind: string): void {
    if (this.group) this.queue.push({ kind: 'end-group' });
    this.group = `${kind}-${Date.now().toString(36)}-${++groupCounter}`;
  }

  get active(): boolean {
    return this.group !== '';
  }

  push(make: () => Edit): void {
    const last = this.queue[this.queue.length - 1];
    if (last && last.kind === 'edit' && last.group === this.group) last.make = make;
    else this.queue.push({ kind: 'edit', group: this.group, make });
    if (!this.busy) void this.flush();
  }

  private async flush(): Promise<void> {
    this.busy = true;
    for (let op = this.queue.shift(); op; op = this.queue.shift()) {
      try {
        if (op.kind === 'end-group') {
          state.status = await api.endGroup();
          renderStatus();
          continue;
        }
        const edit = { ...op.make(), ...(op.group ? { group: op.group } : {}) } as Edit;
        state.status = await api.edit(edit);
        state.error = '';
        renderStatus();
        modelChanged();
      } catch (e) {
        showError(e);
        await reloadModel(); // the server kept its model: show it again
      }
    }
    this.busy = false;
    for (const w of this.waiters.splice(0)) w();
  }

  /** Resolves when every queued operation is done. */
  idle(): Promise<void> {
    return this.busy || this.queue.length ? new Promise((r) => this.waiters.push(r)) : Promise.resolve();
  }

  /** Ends the gesture: its group closes after its last edit. Resolves when all is sent. */
  end(): Promise<void> {
    if (this.group) {
      this.group = '';
      this.queue.push({ kind: 'end-group' });
      if (!this.busy) void this.flush();
    }
    return this.idle();
  }

  /** One edit that is its own undo step. */
  once(kind: string, make: () => Edit): Promise<void> {
    this.begin(kind);
    this.push(make);
    return this.end();
  }
}

const pump = new EditPump();

// ----------------------------------------------------------------------------------------
// Model and selection

function applyState(s: ModelState, fit: boolean): void {
  if (!s.editable) {
    applyViewOnly(s, fit);
    return;
  }
  state.viewOnly = '';
  $('frame-caption').textContent = 'Vertex frames';
  surfaceView.setOverlay($<HTMLInputElement>('overlay').checked);
  const changedTopology =
    !state.model ||
    state.model.vertices.length !== s.model.vertices.length ||
    state.model.frames.length !== s.model.frames.length;
  state.model = s.model;
  state.path = s.path;
  state.status = s;
  $('recovery').hidden = !s.recovery;
  if (changedTopology) {
    state.selectedVertex = null;
    state.selectedFrames.clear();
    state.selectedForce = 0;
  }
  const exportName = $<HTMLInputElement>('export-name');
  if (fit || !exportName.value) exportName.value = s.path.replace(/\.json$/, '');
  refreshScene();
  renderPanel();
  renderStatus();
  if (fit) {
    frameView.fit(modelBox(s.model));
    surfaceView.fit(modelBox(s.model));
  }
}

/** A model the studio shows but does not edit: its curves on the left, the panel idle. */
function applyViewOnly(s: ModelState, fit: boolean): void {
  state.model = null;
  state.viewOnly = (s.model as { type?: string }).type ?? 'this';
  state.path = s.path;
  state.status = s;
  state.selectedVertex = null;
  state.selectedFrames.clear();
  $('recovery').hidden = !s.recovery;  // transforms are journaled: a crash can leave some
  const exportName = $<HTMLInputElement>('export-name');
  if (fit || !exportName.value) exportName.value = s.path.replace(/\.json$/, '');
  const view = s.view ?? { curves: [], spines: [] };
  frameView.showCurves(view.curves, view.spines);
  $('frame-caption').textContent =
    state.viewOnly === 'bspline-pde' ? 'Control nets (view only)' : 'Curves and spine (view only)';
  surfaceView.setOverlay(false);
  renderPanel();
  renderStatus();
  if (fit) {
    const box = pointsBox([...view.curves, ...view.spines]);
    frameView.fit(box);
    surfaceView.fit(box);
  }
}

async function reloadModel(fit = false): Promise<void> {
  try {
    applyState(await api.model(), fit);
  } catch (e) {
    showError(e);
  }
}

async function reloadAll(fit = false): Promise<void> {
  await reloadModel(fit);
  modelChanged();
}

function refreshScene(): void {
  if (!state.model) return;
  frameView.setModel(state.model, state.selectedVertex, state.selectedFrames);
  surfaceView.updateOverlay(state.model, state.selectedFrames);
}

async function refreshFiles(): Promise<void> {
  try {
    const files = await api.files();
    const select = $<HTMLSelectElement>('file-select');
    select.replaceChildren(
      ...files.map((f) => {
        const o = document.createElement('option');
        o.value = o.textContent = f;
        return o;
      }),
    );
    if (files.includes(state.path)) select.value = state.path;
  } catch (e) {
    showError(e);
  }
}

// ----------------------------------------------------------------------------------------
// Vertex dragging and picking (left view)

const canvas = frameView.renderer.domElement;
let drag: { vertex: number; pointer: number } | null = null;
let press: { x: number; y: number; shift: boolean } | null = null;

canvas.addEventListener('pointerdown', (ev) => {
  if (ev.button !== 0 || !state.model) return;
  const vertex = frameView.vertexAt(ev.clientX, ev.clientY);
  if (vertex !== null) {
    frameView.controls.enabled = false; // this listener runs before the controls'
    drag = { vertex, pointer: ev.pointerId };
    canvas.setPointerCapture(ev.pointerId);
    state.selectedVertex = vertex;
    refreshScene();
    renderPanel();
    pump.begin('drag');
    ev.preventDefault();
  } else {
    press = { x: ev.clientX, y: ev.clientY, shift: ev.shiftKey };
  }
});

canvas.addEventListener('pointermove', (ev) => {
  if (!drag && ev.buttons === 0 && state.model && state.model.vertices.length <= 20000) {
    // The cursor tells what a press would do: grab a handle, select a frame, or orbit.
    const cursor =
      frameView.vertexAt(ev.clientX, ev.clientY) !== null
        ? 'grab'
        : frameView.frameAt(ev.clientX, ev.clientY) !== null
          ? 'pointer'
          : '';
    if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
  }
  if (!drag || ev.pointerId !== drag.pointer || !state.model) return;
  const vertex = drag.vertex;
  const target = frameView.dragTarget(state.model.vertices[vertex], ev.clientX, ev.clientY);
  if (!target) return;
  state.model.vertices[vertex] = target;
  frameView.moveVertex(vertex, target);
  surfaceView.moveOverlayVertex(vertex, target);
  renderVertexInputs();
  pump.push(() => ({ op: 'move-vertex', vertex, position: [...state.model!.vertices[vertex]] as Vec3 }));
});

async function endDrag(ev: PointerEvent): Promise<void> {
  if (drag && ev.pointerId === drag.pointer) {
    drag = null;
    frameView.controls.enabled = true;
    await pump.end();
    return;
  }
  if (press && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) < 5) {
    const frame = frameView.frameAt(ev.clientX, ev.clientY);
    if (frame === null) {
      if (!press.shift) state.selectedFrames.clear();
    } else if (press.shift) {
      if (state.selectedFrames.has(frame)) state.selectedFrames.delete(frame);
      else state.selectedFrames.add(frame);
    } else {
      state.selectedFrames = new Set([frame]);
    }
    if (frame === null && !press.shift) state.selectedVertex = null;
    state.selectedForce = 0;
    refreshScene();
    renderPanel();
  }
  press = null;
}
canvas.addEventListener('pointerup', (ev) => void endDrag(ev));
canvas.addEventListener('pointercancel', (ev) => void endDrag(ev));
frameView.attachControls();
surfaceView.attachControls();

// ----------------------------------------------------------------------------------------
// The panel: vertex coordinates, a1 / a2 / f0 sliders with magnification, force regions

const axes = ['x', 'y', 'z'] as const;

function renderVertexInputs(): void {
  const v = state.selectedVertex;
  $('vertex-index').textContent = v === null ? 'none' : `#${v}`;
  axes.forEach((a, i) => {
    const input = $<HTMLInputElement>(`vertex-${a}`);
    input.disabled = v === null;
    if (document.activeElement !== input)
      input.value = v === null || !state.model ? '' : String(+state.model.vertices[v][i].toFixed(5));
  });
}

axes.forEach((a, i) => {
  $<HTMLInputElement>(`vertex-${a}`).addEventListener('change', (ev) => {
    const v = state.selectedVertex;
    const value = Number((ev.target as HTMLInputElement).value);
    if (v === null || !state.model || !Number.isFinite(value)) return;
    const position = [...state.model.vertices[v]] as Vec3;
    position[i] = value;
    state.model.vertices[v] = position;
    refreshScene();
    void pump.once('vertex', () => ({ op: 'move-vertex', vertex: v, position }));
  });
});

/** A power of ten (signed) that puts |value| in (0.1, 1]: the default magnification. */
function niceMagnification(value: number): number {
  if (value === 0 || !Number.isFinite(value)) return 1;
  const m = Math.pow(10, Math.ceil(Math.log10(Math.abs(value)) - 1e-9));
  return Math.sign(value) * Math.max(m, 1);
}

interface SliderRow {
  set(value: number | null): void;
}

/** A slider in [0, 1] with a magnification box; value = slider × magnification. The
 * gesture (pointer down to change) is one undo group. */
function sliderRow(
  parent: HTMLElement,
  id: string,
  label: string,
  onValue: (value: number) => void,
): SliderRow {
  const row = document.createElement('div');
  row.className = 'slider';
  const name = document.createElement('span');
  name.className = 'name';
  name.textContent = label;
  const range = document.createElement('input');
  range.type = 'range';
  range.min = '0';
  range.max = '1';
  range.step = '0.001';
  range.dataset.testid = id;
  const mag = document.createElement('input');
  mag.type = 'number';
  mag.step = 'any';
  mag.title = 'magnification: value = slider × this';
  mag.dataset.testid = `${id}-mag`;
  const value = document.createElement('span');
  value.className = 'value';
  value.dataset.testid = `${id}-value`;
  row.append(name, range, mag, value);
  parent.append(row);

  const current = () => Number(range.value) * Number(mag.value || 1);
  const show = () => (value.textContent = String(+current().toFixed(4)));
  let gesture = false; // from the first input to the change event: one undo group
  range.addEventListener('input', () => {
    if (!gesture) pump.begin(id);
    gesture = true;
    show();
    onValue(current());
  });
  range.addEventListener('change', () => {
    gesture = false;
    void pump.end();
  });
  mag.addEventListener('change', () => {
    show();
    pump.begin(id);
    onValue(current());
    void pump.end();
  });
  return {
    set(v: number | null) {
      row.classList.toggle('disabled', v === null);
      range.disabled = mag.disabled = v === null;
      if (v === null) {
        value.textContent = '';
        return;
      }
      const m = niceMagnification(v);
      mag.value = String(m);
      range.value = String(v / m);
      show();
    },
  };
}

function sub(parent: HTMLElement, text: string): void {
  const d = document.createElement('div');
  d.className = 'sub';
  d.textContent = text;
  parent.append(d);
}

const selectedFrameList = () => [...state.selectedFrames].sort((a, b) => a - b);
const firstFrame = () => (state.model && state.selectedFrames.size ? state.model.frames[selectedFrameList()[0]] : null);

// a1, a2: set-parameters over the selected frames.
const parameterRows: Record<'a1' | 'a2', SliderRow[]> = { a1: [], a2: [] };
{
  const parent = document.getElementById('parameters')!;
  for (const p of ['a1', 'a2'] as const) {
    sub(parent, `${p} (x, y, z)`);
    axes.forEach((a, i) => {
      parameterRows[p].push(
        sliderRow(parent, `${p}-${a}`, `${p}.${a}`, (value) => {
          const frames = selectedFrameList();
          const frame = firstFrame();
          if (!frame || !state.model) return;
          const vec = [...(frame[p] ?? [1, 1, 1])] as Vec3;
          vec[i] = value;
          for (const f of frames) state.model.frames[f][p] = [...vec] as Vec3;
          pump.push(() => ({ op: 'set-parameters', frames, [p]: vec }) as Edit);
        }),
      );
    });
  }
}

// f0 of the selected force: set-forces for one frame, set-shared-forces for several.
const forceRows: SliderRow[] = [];
{
  const parent = document.getElementById('force-sliders')!;
  sub(parent, 'f0 (x, y, z) of the selected force');
  axes.forEach((a, i) => {
    forceRows.push(
      sliderRow(parent, `f0-${a}`, `f0.${a}`, (value) => {
        const model = state.model;
        if (!model) return;
        const frames = selectedFrameList();
        if (frames.length === 1) {
          const frame = model.frames[frames[0]];
          const force = frame.forces?.[state.selectedForce];
          if (!force) return;
          force.f0 = [...force.f0] as Vec3;
          force.f0[i] = value;
          const forces = structuredClone(frame.forces!);
          pump.push(() => ({ op: 'set-forces', frame: frames[0], forces }));
        } else if (frames.length > 1) {
          model.forces ??= [];
          let shared = sharedForceOf(frames);
          if (!shared) {
            shared = { f0: [0, 0, 0], frames };
            model.forces.push(shared);
          }
          shared.f0 = [...shared.f0] as Vec3;
          shared.f0[i] = value;
          const forces = structuredClone(model.forces);
          pump.push(() => ({ op: 'set-shared-forces', forces }));
          renderForceList();
        }
      }),
    );
  });
}

function sharedForceOf(frames: number[]): SharedForce | undefined {
  const key = frames.join(',');
  return state.model?.forces?.find((f) => [...f.frames].sort((a, b) => a - b).join(',') === key);
}

function renderForceList(): void {
  const list = $('force-list');
  list.replaceChildren();
  const model = state.model;
  const frames = selectedFrameList();
  const add = $<HTMLButtonElement>('add-force');
  add.disabled = frames.length !== 1;
  if (!model || frames.length === 0) {
    list.textContent = 'Select a frame to edit its forces.';
    list.className = 'forces muted';
    forceRows.forEach((r) => r.set(null));
    return;
  }
  list.className = 'forces';
  if (frames.length > 1) {
    const shared = sharedForceOf(frames);
    const item = document.createElement('div');
    item.className = 'force shared selected';
    item.dataset.testid = 'shared-force';
    item.textContent = shared
      ? `shared force over frames ${frames.join(', ')}: f0 = [${shared.f0.map((x) => +x.toFixed(3)).join(', ')}]`
      : `no shared force over frames ${frames.join(', ')} yet: move an f0 slider to add one`;
    list.append(item);
    const f0 = shared?.f0 ?? [0, 0, 0];
    forceRows.forEach((r, i) => r.set(f0[i]));
    return;
  }
  const f = frames[0];
  const forces = model.frames[f].forces ?? [];
  if (state.selectedForce >= forces.length) state.selectedForce = Math.max(0, forces.length - 1);
  if (forces.length) {
    const head = document.createElement('div');
    head.className = 'force head';
    for (const text of ['', 'u0', 'u1', 'v0', 'v1', '']) {
      const cell = document.createElement('span');
      cell.textContent = text;
      head.append(cell);
    }
    list.append(head);
  }
  forces.forEach((force, k) => {
    const item = document.createElement('div');
    item.className = `force${k === state.selectedForce ? ' selected' : ''}`;
    item.dataset.testid = `force-${k}`;
    const tag = document.createElement('span');
    tag.className = 'tag';
    tag.textContent = `#${k}`;
    item.append(tag);
    const region: Region = force.region ?? [0, 1, 0, 1];
    ['u0', 'u1', 'v0', 'v1'].forEach((name, j) => {
      const input = document.createElement('input');
      input.type = 'number';
      input.step = '0.05';
      input.min = '0';
      input.max = '1';
      input.title = name;
      input.value = String(region[j]);
      input.dataset.testid = `force-${k}-${name}`;
      input.addEventListener('change', () => {
        const next = [...region] as Region;
        next[j] = Number(input.value);
        force.region = next;
        const all = structuredClone(forces);
        void pump.once('region', () => ({ op: 'set-forces', frame: f, forces: all }));
      });
      item.append(input);
    });
    const remove = document.createElement('button');
    remove.textContent = '×';
    remove.title = 'Remove this force';
    remove.dataset.testid = `force-${k}-remove`;
    remove.addEventListener('click', (ev) => {
      ev.stopPropagation();
      const all = forces.filter((_, j) => j !== k);
      model.frames[f].forces = all;
      renderForceList();
      void pump.once('force', () => ({ op: 'set-forces', frame: f, forces: structuredClone(all) }));
    });
    item.append(remove);
    item.addEventListener('click', () => {
      state.selectedForce = k;
      renderForceList();
    });
    list.append(item);
  });
  if (forces.length === 0) {
    const none = document.createElement('div');
    none.className = 'muted';
    none.textContent = `Frame ${f} has no force.`;
    list.append(none);
  }
  const force = forces[state.selectedForce];
  forceRows.forEach((r, i) => r.set(force ? force.f0[i] : null));
}

$('add-force').addEventListener('click', () => {
  const frames = selectedFrameList();
  const model = state.model;
  if (!model || frames.length !== 1) return;
  const frame = model.frames[frames[0]];
  const forces: FrameForce[] = [...(frame.forces ?? []), { f0: [0, 0, 0], region: [0.25, 0.75, 0.25, 0.75] }];
  frame.forces = forces;
  state.selectedForce = forces.length - 1;
  renderForceList();
  void pump.once('force', () => ({ op: 'set-forces', frame: frames[0], forces: structuredClone(forces) }));
});

function renderPanel(): void {
  // Vertex, frame and force tools only mean something for a vertex-frame model.
  $('frame-tools').hidden = state.viewOnly !== '';
  renderVertexInputs();
  const frames = selectedFrameList();
  $('frame-selection').textContent = frames.length ? frames.map((f) => `#${f}`).join(' ') : 'none';
  const frame = firstFrame();
  for (const p of ['a1', 'a2'] as const)
    parameterRows[p].forEach((r, i) => r.set(frame ? (frame[p] ?? [1, 1, 1])[i] : null));
  renderForceList();
}

// ----------------------------------------------------------------------------------------
// Transform: the whole model, any type, one undo step each

/** The bounding box of the page's surface mesh (null before the first mesh). */
function meshBox(): { min: Vec3; max: Vec3 } | null {
  const p = state.mesh?.positions;
  if (!p || p.length < 3) return null;
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3)
    for (let c = 0; c < 3; ++c) {
      min[c] = Math.min(min[c], p[i + c]);
      max[c] = Math.max(max[c], p[i + c]);
    }
  return { min, max };
}

/** Where rotations and scaling pivot: the centre of the surface's bounding box (of the
 * vertices while there is no mesh yet). */
function modelCenter(): Vec3 {
  const box = meshBox();
  if (box) return [0, 1, 2].map((c) => (box.min[c] + box.max[c]) / 2) as Vec3;
  if (state.model) {
    const b = modelBox(state.model);
    return [(b.min.x + b.max.x) / 2, (b.min.y + b.max.y) / 2, (b.min.z + b.max.z) / 2];
  }
  return [0, 0, 0];
}

function numberOf(id: string): number {
  const input = $<HTMLInputElement>(id);
  const value = Number(input.value);
  if (input.value.trim() === '' || !Number.isFinite(value)) throw new Error(`${input.title}: type a number`);
  return value;
}

async function applyTransform(what: string, make: () => Transform): Promise<void> {
  await run(async () => {
    state.status = await api.transform(make());
    state.message = what;
    await reloadAll(true); // the views follow the model (the grid shows where it went)
  });
}

$('move-apply').addEventListener('click', () =>
  void applyTransform('moved the model', () => ({
    translate: [numberOf('move-x'), numberOf('move-y'), numberOf('move-z')],
  })),
);
$('rotate-apply').addEventListener('click', () =>
  void applyTransform('rotated the model', () => {
    const axis: Vec3 = [0, 0, 0];
    axis[['x', 'y', 'z'].indexOf($<HTMLSelectElement>('rotate-axis').value)] = 1;
    return { rotate: { axis, degrees: numberOf('rotate-degrees') }, center: modelCenter() };
  }),
);
$('scale-apply').addEventListener('click', () =>
  void applyTransform('scaled the model', () => ({ scale: numberOf('scale-factor'), center: modelCenter() })),
);

// ----------------------------------------------------------------------------------------
// Toolbar

async function run(action: () => Promise<void>): Promise<void> {
  try {
    await pump.end();
    await action();
    state.error = '';
  } catch (e) {
    showError(e);
  }
  renderStatus();
}

async function undo(): Promise<void> {
  await run(async () => {
    state.status = await api.undo();
    await reloadAll();
  });
}
async function redo(): Promise<void> {
  await run(async () => {
    state.status = await api.redo();
    await reloadAll();
  });
}

$('undo').addEventListener('click', () => void undo());
$('redo').addEventListener('click', () => void redo());
document.addEventListener('keydown', (ev) => {
  const target = ev.target as HTMLElement;
  if (target instanceof HTMLInputElement && (target.type === 'text' || target.type === 'number')) return;
  if (!(ev.ctrlKey || ev.metaKey)) return;
  const key = ev.key.toLowerCase();
  if (key === 'z' && !ev.shiftKey) {
    ev.preventDefault();
    void undo();
  } else if ((key === 'z' && ev.shiftKey) || key === 'y') {
    ev.preventDefault();
    void redo();
  }
});

$('open').addEventListener('click', () =>
  void run(async () => {
    const path = $<HTMLSelectElement>('file-select').value;
    if (!path) return;
    await api.open(path);
    state.message = `opened ${path}`;
    await reloadAll(true);
  }),
);
$('save').addEventListener('click', () =>
  void run(async () => {
    const s = await api.save();
    state.message = `saved ${s.path}`;
    await reloadModel();
  }),
);
$('save-as').addEventListener('click', () =>
  void run(async () => {
    const input = $<HTMLInputElement>('saveas-path');
    let path = input.value.trim();
    if (!path) throw new Error('Save as: type a file name (.json) first');
    if (!path.endsWith('.json')) path += '.json';
    const s = await api.saveAs(path);
    state.message = `saved as ${s.path}`;
    await reloadModel();
    await refreshFiles();
  }),
);
for (const ext of ['obj', 'stl', 'glb'] as const) {
  $(`export-${ext}`).addEventListener('click', () =>
    void run(async () => {
      const name = $<HTMLInputElement>('export-name').value.trim() || 'surface';
      const r = await api.exportMesh(`${name}.${ext}`);
      state.message = `exported ${r.path} (${plural(r.triangles, 'triangle')})`;
    }),
  );
}
$('recover').addEventListener('click', () =>
  void run(async () => {
    await api.recover();
    state.message = 'recovered the autosave';
    await reloadAll(true);
  }),
);
$('discard').addEventListener('click', () =>
  void run(async () => {
    await api.discardRecovery();
    state.message = 'discarded the autosave';
    await reloadModel();
  }),
);
$('create').addEventListener('click', () => void requestMesh());
$('live').addEventListener('change', () => {
  if (live() && state.meshStale) void requestMesh();
});
$('resolution').addEventListener('change', () => void requestMesh());
$<HTMLInputElement>('zebra').addEventListener('change', (ev) =>
  surfaceView.setZebra((ev.target as HTMLInputElement).checked),
);
$<HTMLInputElement>('overlay').addEventListener('change', (ev) =>
  surfaceView.setOverlay((ev.target as HTMLInputElement).checked && !state.viewOnly),
);

// ----------------------------------------------------------------------------------------
// Start

function frame(): void {
  frameView.renderIfNeeded();
  surfaceView.renderIfNeeded();
  requestAnimationFrame(frame);
}

declare global {
  interface Window {
    __studio: unknown;
  }
}

/** Hooks for the browser tests: where things are on screen, and edits through the page. */
window.__studio = {
  vertexScreen: (i: number) => frameView.vertexScreen(i),
  frameScreen: (f: number) => frameView.frameScreen(f),
  edit: (edit: Edit) => pump.once('test', () => edit).then(() => state.error),
  idle: () => pump.idle(),
  /** Whether the page's mesh (updated by deltas) equals the whole mesh the server makes now. */
  meshMatchesServer: async () => {
    const m = state.mesh;
    if (!m) return false;
    const full = await api.mesh({ resolution: m.resolution });
    if (full.kind !== 'full' || full.revision !== m.revision) return false;
    const same = (a: ArrayLike<number>, b: ArrayLike<number>) => a.length === b.length && Array.prototype.every.call(a, (x: number, i: number) => x === b[i]);
    return same(full.positions, m.positions) && same(full.normals, m.normals) && same(full.indices, m.indices);
  },
  renderTimes: (n: number) => ({
    frames: Array.from({ length: n }, () => frameView.renderTimed()),
    surface: Array.from({ length: n }, () => surfaceView.renderTimed()),
  }),
  state: () => ({ revision: state.status?.revision, mesh: state.mesh?.revision, error: state.error, meshDeltas }),
  /** The bounding box of the page's surface mesh. */
  meshBox,
};

renderPanel();
renderStatus();
frame();
void (async () => {
  await reloadAll(true);
  await refreshFiles();
  document.body.dataset.ready = 'true';
})();
