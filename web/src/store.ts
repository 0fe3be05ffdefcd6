// The page's state and the one way to change it (as the three.js editor's Editor and its
// signals): every write goes through Store.update, which names the topics it touched; the renderers subscribed to those topics run once, together, in the
// next microtask. Nothing else writes the state or calls a renderer.
import type { MeshData, Model, ModelView, ShapeSettings, Status, Vec3 } from './api';
import type { ShapeHandles } from './shape';

export interface State {
  /** The model file, relative to the studio's root. */
  path: string;
  /** The editable (vertex-frame) model: the page's copy, updated as edits are sent. */
  model: Model | null;
  /** Whether the model has editable parts (vertex frames: the frame tools edit them; the
   * library's SurfaceMethod::hasEditableParts); without them the page drags the handles the
   * server sends. */
  hasEditableParts: boolean;
  /** The model's type (the server's name for its method), or '' before one is open. */
  modelType: string;
  /** The curves and spines of a model without editable parts. */
  view: ModelView | null;
  /** What the server says a model without editable parts (spectral, cross-section, B-spline
   * PDE) offers to drag (its method's handles), else null: curve-editor.ts drags them. */
  handles: ShapeHandles | null;
  /** What the server says such a model offers to set whole (its method's settings), else
   * null: curve-editor.ts's panels show them. */
  settings: ShapeSettings | null;
  status: Status | null;
  /** An autosave differs from the file (offer to recover it). */
  recovery: boolean;
  selectedVertex: number | null;
  /** The selected vertices in the order they were picked (the modeller's tools read the
   * order: add-frame's corners, weld's kept vertex); holds selectedVertex when that is set. */
  selectedVertices: number[];
  selectedFrames: Set<number>;
  /** The selected force of a single selected frame (index in its forces). */
  selectedForce: number;
  /** The 3D cursor: a point the user places (cursor-tool.ts), a pivot for rotate and scale;
   * the view's, not the model's (kept by the browser per model file, never in the file). */
  cursor: Vec3;
  mesh: MeshData | null;
  /** Live is off and the model changed since the last mesh. */
  meshStale: boolean;
  /** Meshes that came as deltas (tests). */
  meshDeltas: number;
  error: string;
  message: string;
}

/** What a change touched: the renderers subscribe to these.
 * - model: the model was replaced or edited as a whole (rebuild views and panel)
 * - vertex: the selected vertex moved (a drag, a typed coordinate)
 * - selection: the selected vertex, frames or force
 * - forces: the forces of the selection (the force list)
 * - mesh: a new surface mesh (or its staleness)
 * - status: revision, undo depth, dirty, path, recovery, error, message
 * - cursor: the 3D cursor moved */
export type Topic = 'model' | 'vertex' | 'selection' | 'forces' | 'mesh' | 'status' | 'cursor';

export type Listener = (state: Readonly<State>, topics: ReadonlySet<Topic>) => void;

export function initialState(): State {
  return {
    path: '',
    model: null,
    hasEditableParts: true,
    modelType: '',
    view: null,
    handles: null,
    settings: null,
    status: null,
    recovery: false,
    selectedVertex: null,
    selectedVertices: [],
    selectedFrames: new Set(),
    selectedForce: 0,
    cursor: [0, 0, 0],
    mesh: null,
    meshStale: false,
    meshDeltas: 0,
    error: '',
    message: '',
  };
}

export class Store {
  private readonly current: State;
  private readonly listeners: { topics: ReadonlySet<Topic>; fn: Listener }[] = [];
  private pending = new Set<Topic>();
  private scheduled = false;

  constructor(state: State = initialState()) {
    this.current = state;
  }

  /** The state, to read (write it through update). */
  get state(): Readonly<State> {
    return this.current;
  }

  /** Calls `fn` after every change that touched one of `topics` (once per batch). */
  subscribe(topics: Topic[], fn: Listener): () => void {
    const entry = { topics: new Set(topics), fn };
    this.listeners.push(entry);
    return () => {
      const i = this.listeners.indexOf(entry);
      if (i >= 0) this.listeners.splice(i, 1);
    };
  }

  /** Changes the state and schedules the renderers of `topics`. An empty `topics` is a
   * change nothing needs to redraw (the control that made it already shows it). */
  update(topics: Topic[], change: (state: State) => void): void {
    change(this.current);
    for (const t of topics) this.pending.add(t);
    if (topics.length && !this.scheduled) {
      this.scheduled = true;
      queueMicrotask(() => this.flush());
    }
  }

  /** Runs the renderers of the topics changed since the last flush, now. */
  flush(): void {
    this.scheduled = false;
    if (!this.pending.size) return;
    const topics = this.pending;
    this.pending = new Set();
    for (const { topics: wanted, fn } of [...this.listeners])
      if ([...wanted].some((t) => topics.has(t))) fn(this.current, topics);
  }
}
