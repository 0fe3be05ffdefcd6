// The studio's context (the three.js editor's `editor`): the store, the two views, the
// edit pump and the mesh sync, and the actions every part of the page shares (load the
// model, report an error, run a toolbar action). Panels, toolbar and tools get it and
// subscribe to the store; none holds page state of its own.
import { api, ApiError } from './api';
import type { ModelState } from './api';
import { $ } from './dom';
import { MeshSync } from './mesh-sync';
import { EditPump } from './pump';
import { PREVIEW_PIXEL_SCALE, previewResolution } from './preview';
import { FrameView, SurfaceView, modelBox, pointsBox } from './scene';
import { Store } from './store';

/** Whether gestures show a coarser preview (off with ?preview=0, for comparisons). */
const PREVIEW = new URLSearchParams(location.search).get('preview') !== '0';

export class Studio {
  readonly store = new Store();
  readonly frameView = new FrameView($('frame-view'));
  readonly surfaceView = new SurfaceView($('surface-view'));
  readonly pump: EditPump;
  readonly meshes: MeshSync;
  /** Whether a drag or slider gesture is in progress (the surface may show a preview). */
  gesture = false;

  constructor() {
    this.pump = new EditPump({
      edit: (edit) => api.edit(edit),
      endGroup: () => api.endGroup(),
      answered: (status, edited) => {
        this.store.update(['status'], (s) => {
          s.status = status;
          if (edited) s.error = '';
        });
        if (edited) this.modelChanged();
      },
      refused: async (e) => {
        this.showError(e);
        await this.reloadModel(); // the server kept its model: show it again
      },
    });
    this.meshes = new MeshSync({
      mesh: (options) => api.mesh(options),
      resolution: () => this.resolution(),
      current: () => this.store.state.mesh,
      replaced: (mesh) => {
        this.surfaceView.setMesh(mesh);
        this.store.update(['mesh'], (s) => {
          s.mesh = mesh;
          s.meshStale = false;
        });
      },
      updated: (_mesh, delta) => {
        this.surfaceView.updateVertices(delta.runs);
        this.store.update(['mesh'], (s) => {
          ++s.meshDeltas;
          s.meshStale = false;
        });
      },
      failed: (e) => this.showError(e),
    });
  }

  /** The resolution chosen in the surface view's bar. */
  fullResolution(): number {
    return Number($<HTMLSelectElement>('resolution').value);
  }

  /** The resolution to fetch now: the chosen one, or a coarser preview during a gesture
   * (preview.ts; ?preview=0 turns it off). */
  resolution(): number {
    const full = this.fullResolution();
    const mesh = this.store.state.mesh;
    if (!this.gesture || !PREVIEW || !mesh || mesh.resolution < 2) return full;
    // The full mesh's triangles, from the mesh shown (triangles grow as (resolution - 1)²).
    const fullTriangles = mesh.triangleCount * ((full - 1) / (mesh.resolution - 1)) ** 2;
    return previewResolution(full, fullTriangles);
  }

  /** Starts a drag or slider gesture: its edits are one undo group. A large surface is
   * previewed coarser (resolution(): the next mesh) and at a lower pixel density. */
  beginGesture(kind: string): void {
    this.gesture = true;
    this.pump.begin(kind);
    if (this.resolution() !== this.fullResolution()) this.surfaceView.setPixelScale(PREVIEW_PIXEL_SCALE);
  }

  /** Ends the gesture; resolves when its edits are answered. A preview gives way to the
   * full resolution at once (the request goes beside the gesture's last edits; the
   * surface sync fetches again after them). */
  async endGesture(): Promise<void> {
    this.gesture = false;
    this.surfaceView.setPixelScale(1);
    const mesh = this.store.state.mesh;
    if (mesh && mesh.resolution !== this.fullResolution()) this.modelChanged();
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
    const editable = m.editable;
    const changedTopology =
      !editable ||
      !before ||
      before.vertices.length !== m.model.vertices.length ||
      before.frames.length !== m.model.frames.length;
    store.update(['model', 'status', 'selection', 'forces'], (s) => {
      s.model = editable ? m.model : null;
      s.viewOnly = editable ? '' : ((m.model as { type?: string }).type ?? 'this');
      s.view = editable ? null : (m.view ?? { curves: [], spines: [] });
      s.path = m.path;
      s.status = m;
      s.recovery = m.recovery;
      if (changedTopology) {
        s.selectedVertex = null;
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

  /** A toolbar action: after the edits in flight; its error shown, a success clears it. */
  async run(action: () => Promise<void>): Promise<void> {
    try {
      await this.pump.end();
      await action();
      this.store.update(['status'], (s) => (s.error = ''));
    } catch (e) {
      this.showError(e);
    }
  }
}
