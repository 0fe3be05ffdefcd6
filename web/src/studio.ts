// The studio's context (the three.js editor's `editor`): the store, the two views, the
// edit pump and the mesh sync, and the actions every part of the page shares (load the
// model, report an error, run a toolbar action). Panels, toolbar and tools get it and
// subscribe to the store; none holds page state of its own.
import { api, ApiError } from './api';
import type { MeshOptions, ModelState } from './api';
import { $ } from './dom';
import { MeshSync } from './mesh-sync';
import { EditPump } from './pump';
import { previewResolution } from './preview';
import { FrameView } from './frame-view';
import { SurfaceView } from './surface-view';
import { modelBox, pointsBox } from './viewport';
import { Store } from './store';
import type { MeshData } from './wire';

/** Whether gestures show a coarser preview (off with ?preview=0, for comparisons). */
const PREVIEW = new URLSearchParams(location.search).get('preview') !== '0';

export class Studio {
  readonly store = new Store();
  readonly frameView = new FrameView($('frame-view'));
  readonly surfaceView = new SurfaceView($('surface-view'));
  readonly pump: EditPump;
  readonly meshes: MeshSync;
  /** The solver of every mesh request (solver.ts): the global one unless set. */
  solver: Pick<MeshOptions, 'solver' | 'seed'> = {};
  /** Whether a drag or slider gesture is in progress (the surface may show a preview). */
  gesture = false;

  constructor() {
    this.pump = new EditPump({
      // With Live on, an edit brings the mesh after it (one round trip), unless a mesh
      // request is in flight (then the mesh follows the answer).
      edit: async (edit) =>
        (this.live() ? await this.meshes.along((options) => api.editWithMesh(edit, { ...options, ...this.solver })) : null) ??
        api.edit(edit),
      endGroup: () => api.endGroup(),
      answered: (status, edited) => {
        this.store.update(['status'], (s) => {
          s.status = status;
          if (edited) s.error = '';
        });
        if (edited && !this.showing(status.revision)) this.modelChanged();
      },
      refused: async (e) => {
        this.showError(e);
        await this.reloadModel(); // the server kept its model: show it again
      },
    });
    this.meshes = new MeshSync({
      mesh: (options) => api.mesh({ ...options, ...this.solver }),
      resolution: () => this.resolution(),
      replaced: (mesh, dropped) => {
        if (dropped) this.surfaceView.dropMesh(dropped);
        this.show(mesh);
        this.store.update(['mesh'], (s) => {
          s.mesh = mesh;
          s.meshStale = false;
        });
      },
      updated: (mesh, delta) => {
        this.show(mesh, delta.runs);
        this.store.update(['mesh'], (s) => {
          s.mesh = mesh;
          ++s.meshDeltas;
          s.meshStale = false;
        });
      },
      failed: (e) => {
        if (!this.gesture) this.surfaceView.setPreview(false);
        this.showError(e);
      },
    });
  }

  /** Shows a mesh; the chosen resolution outside a gesture is drawn at full pixel density
   * again (kept at the preview's until then: no frame of the preview at full density). */
  private show(mesh: MeshData, runs?: Uint32Array): void {
    if (!this.gesture && mesh.resolution === this.fullResolution()) this.surfaceView.setPreview(false);
    this.surfaceView.showMesh(mesh, runs);
  }

  /** Whether the surface shown is that of `revision` at the resolution wanted now (an edit
   * that brought its mesh needs no other). */
  private showing(revision: number): boolean {
    const mesh = this.store.state.mesh;
    return !!mesh && mesh.revision === revision % 2 ** 32 && mesh.resolution === this.resolution();
  }

  /** The resolution chosen in the surface view's bar. */
  fullResolution(): number {
    return Number($<HTMLSelectElement>('resolution').value);
  }

  /** The resolution to fetch now: the chosen one, or a coarser preview during a gesture
   * (preview.ts; ?preview=0 turns it off). */
  resolution(): number {
    const full = this.fullResolution();
    return this.gesture && PREVIEW && this.preview ? Math.min(this.preview, full) : full;
  }

  /** The preview's resolution of the gesture in progress, chosen once when it begins (a
   * resolution that changed within a gesture would cost whole meshes and the full
   * resolution's delta base); 0 before the first mesh. */
  private preview = 0;

  /** The resolution a gesture previews at, from the triangles of the full-resolution mesh
   * held, else of the mesh shown (they grow as (resolution − 1)²). */
  private previewFor(): number {
    const full = this.fullResolution();
    const mesh = this.meshes.heldAt(full) ?? this.store.state.mesh;
    if (!mesh || mesh.resolution < 2) return 0;
    const fullTriangles = mesh.triangleCount * ((full - 1) / (mesh.resolution - 1)) ** 2;
    return previewResolution(full, fullTriangles);
  }

  /** Whether the surface is fetched coarser than the chosen resolution now (a gesture's
   * preview of a large model). */
  previewing(): boolean {
    return this.resolution() !== this.fullResolution();
  }

  /** Starts a drag or slider gesture: its edits are one undo group. A large surface is
   * previewed coarser (resolution(): the next mesh) and at a lower pixel density. */
  beginGesture(kind: string): void {
    this.gesture = true;
    this.preview = this.previewFor();
    this.pump.begin(kind);
    if (this.previewing()) this.surfaceView.setPreview(true);
  }

  /** Ends the gesture; resolves when its edits are answered. A preview gives way to the
   * full resolution at once (the request goes beside the gesture's last edits; the
   * surface sync fetches again after them). */
  async endGesture(): Promise<void> {
    this.gesture = false;
    const mesh = this.store.state.mesh;
    if (mesh && mesh.resolution !== this.fullResolution() && this.live()) this.modelChanged();
    else this.surfaceView.setPreview(false);
    await this.pump.end();
  }

  live(): boolean {
    return $<HTMLInputElement>('live').checked;
  }

  showError(e: unknown): void {
    const message = e instanceof ApiError || e instanceof Error ? e.message : String(e);
    this.store.update(['status'], (s) => (s.error = message));
  }

  say(message: string): void {
    this.store.update(['status'], (s) => (s.message = message));
  }

  /** The server's model changed: fetch its surface (or mark it stale when Live is off). */
  modelChanged(): void {
    if (this.live()) void this.meshes.request();
    else this.store.update(['mesh'], (s) => (s.meshStale = true));
  }

  /** Shows the server's model state; `fit` points both cameras at it. */
  applyState(m: ModelState, fit: boolean): void {
    const store = this.store;
    const before = store.state.model;
    const editable = m.hasEditableParts;
    const changedTopology =
      !editable ||
      !before ||
      before.vertices.length !== m.model.vertices.length ||
      before.frames.length !== m.model.frames.length;
    store.update(['model', 'status', 'selection', 'forces'], (s) => {
      s.model = editable ? m.model : null;
      s.hasEditableParts = editable;
      s.modelType = m.type;
      s.view = editable ? null : (m.view ?? { curves: [], spines: [] });
      s.handles = editable ? null : (m.handles ?? null);
      s.settings = editable ? null : (m.settings ?? null);
      s.path = m.path;
      s.status = m;
      s.recovery = m.recovery;
      if (changedTopology) {
        s.selectedVertex = null;
        s.selectedVertices = [];
        s.selectedFrames = new Set();
        s.selectedForce = 0;
      }
    });
    if (fit) {
      const box = editable ? modelBox(m.model) : pointsBox([...(m.view?.curves ?? []), ...(m.view?.spines ?? [])]);
      this.frameView.fit(box);
      this.surfaceView.fit(box);
    }
  }

  async reloadModel(fit = false): Promise<void> {
    try {
      this.applyState(await api.model(), fit);
    } catch (e) {
      this.showError(e);
    }
  }

  async reloadAll(fit = false): Promise<void> {
    await this.reloadModel(fit);
    this.modelChanged();
  }

  /** The toolbar actions not yet finished, in order (run()). */
  private actions: Promise<void> = Promise.resolve();

  /** A toolbar action: after the edits in flight and after every action before it, the
   * model it reloads included (a transform typed twice, or one after an undo, starts from
   * the server's model as the one before left it, never from a page copy a reload is still
   * replacing); its error shown, a success clears it. */
  run(action: () => Promise<void>): Promise<void> {
    const next = this.actions.then(async () => {
      try {
        await this.pump.end();
        await action();
        this.store.update(['status'], (s) => (s.error = ''));
      } catch (e) {
        this.showError(e);
      }
    });
    this.actions = next;
    return next;
  }
}
