// The typed client of the studio server's API (apps/studio/README.md). Every request of
// the front-end goes through this module, and carries the studio's per-launch token.
import { ApiError, parseMesh } from './wire';
import type { MeshData, MeshDelta } from './wire';
import type { ShapeHandles } from './shape';

export { ApiError, applyDelta, parseMesh } from './wire';
export type { MeshData, MeshDelta } from './wire';

export type Vec3 = [number, number, number];
export type Region = [number, number, number, number];

export interface FrameForce {
  f0: Vec3;
  region?: Region;
}
export interface Frame {
  vertices: number[];
  a1?: Vec3;
  a2?: Vec3;
  forces?: FrameForce[];
}
export interface SharedForce {
  f0: Vec3;
  frames: number[];
}
export interface Model {
  type: 'vertex-frames';
  name?: string;
  description?: string;
  vertices: Vec3[];
  frames: Frame[];
  forces?: SharedForce[];
}

/** The session status every edit, undo and redo answers with. */
export interface Status {
  revision: number;
  undo: number;
  redo: number;
  dirty: boolean;
}
/** What the frame view draws of a model without editable parts (spectral, cross-sections,
 * B-spline PDE). */
export interface ModelView {
  /** Position curves of the conditions, closed, sampled around v. */
  curves: Vec3[][];
  /** The spine A0(u) of each patch. */
  spines: Vec3[][];
}

/** The operator of a model as set-operator's fields at the model's values (the fields the
 * model takes: a spectral model's operator and N, a chain's method). */
export interface OperatorSettings {
  operator?: 'ugail' | 'fu';
  N?: number;
  a: number;
  modes: number;
  remainder: boolean;
  method?: 'global' | 'c2' | 'shared-curves';
}
/** What a model without editable parts offers to set whole (SurfaceMethod::settings). */
export interface ShapeSettings {
  /** The ops of the edits the model takes. */
  edits: string[];
  /** What the frame view draws of it, as its caption names it. */
  overlay: string;
  operator?: OperatorSettings;
}

export interface ModelState extends Status {
  path: string;
  recovery: boolean;
  /** The model's type (its method's type name: "vertex-frames", "spectral", ...). */
  type: string;
  /** Whether the model has editable parts (vertex frames; SurfaceMethod::hasEditableParts):
   * false for spectral, cross-section and B-spline PDE models, edited by their handles. */
  hasEditableParts: boolean;
  /** The model as its file says: the page reads it only when it has editable parts (a
   * vertex-frames Model); else it is only passed on. */
  model: Model;
  view?: ModelView;
  /** Models without editable parts: what their method offers to drag (SurfaceMethod::handles). */
  handles?: ShapeHandles;
  /** Models without editable parts: what they offer to set whole (SurfaceMethod::settings). */
  settings?: ShapeSettings;
  /** Shape models: what to know before dragging a point ("" when a drag stays local). */
  dragAdvice?: string;
}
export interface FileStatus extends Status {
  path: string;
  recovery?: boolean;
}
/** What POST /api/export wrote: a mesh (vertices, triangles) or a CAD file (faces). */
export interface ExportResult {
  path: string;
  vertices?: number;
  triangles?: number;
  faces?: number;
  exactFaces?: number;
  maxDeviation?: number;
}

export type Edit =
  | { op: 'move-vertex'; vertex: number; position: Vec3; group?: string }
  | { op: 'set-parameters'; frames: number[]; a1?: Vec3; a2?: Vec3; group?: string }
  | { op: 'set-forces'; frame: number; forces: FrameForce[]; group?: string }
  | { op: 'set-shared-forces'; forces: SharedForce[]; group?: string }
  | { op: 'move-vertices'; vertices: number[]; positions: Vec3[]; group?: string }
  // The structure edits (sides: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0).
  | { op: 'extrude'; edges: { frame: number; side: number }[]; distance?: number }
  | { op: 'add-frame'; corners: number[] }
  | { op: 'delete-frames'; frames: number[] }
  | { op: 'flip-frames'; frames: number[] }
  | { op: 'mirror-frames'; frames: number[]; axis: 'x' | 'y' | 'z'; at?: number }
  | { op: 'split-frame'; frames: number[]; parts: 4 }
  | { op: 'split-frame'; frames: number[]; parts: 2; across: 'u' | 'v' }
  | { op: 'weld-vertices'; vertices: [number, number] }
  | { op: 'weld-edges'; edges: { frame: number; side: number }[] }
  // The shape edits of the other model types (shape.ts: ShapeEdit).
  | import('./shape').ShapeEdit;

/** A new model (POST /api/new): one frame, a u × v grid, or a tube of u frames round z. */
export interface NewModel {
  path: string;
  kind: 'single' | 'grid' | 'tube';
  u?: number;
  v?: number;
  size?: number;
}

/** A whole-model transform (POST /api/transform), of any model type: scale about
 * `center`, then rotate (about its own center, else `center`), then translate. */
export interface Transform {
  translate?: Vec3;
  rotate?: { axis: Vec3; degrees: number; center?: Vec3 };
  scale?: number;
  center?: Vec3;
}

export interface MeshOptions {
  /** The id of the mesh the client has: the server may answer with a delta against it. */
  base?: number;
  resolution?: number;
  solver?: 'global' | 'local';
  seed?: number;
}

async function failure(res: Response): Promise<ApiError> {
  let message = `HTTP ${res.status}`;
  try {
    const body = (await res.json()) as { error?: string };
    if (body && typeof body.error === 'string') message = body.error;
  } catch {
    /* not JSON: keep the status */
  }
  return new ApiError(res.status, message);
}

/** The header that carries the token (apps/studio/README.md, "Security"). */
export const TOKEN_HEADER = 'X-Pdesurf-Token';
const TOKEN_KEY = 'pdesurf-token';

/** The studio's per-launch token: taken from the page's address (`?token=`, as `pdesurf
 * studio` prints it), which then loses it (history.replaceState: it stays out of the
 * history, bookmarks and screenshots); kept in sessionStorage so that reloading this tab
 * works. A token in the address replaces a kept one (a restarted studio has a new one). */
function takeToken(): string {
  const url = new URL(window.location.href);
  const given = url.searchParams.get('token');
  if (given === null) {
    try {
      return sessionStorage.getItem(TOKEN_KEY) ?? '';
    } catch {
      return '';
    }
  }
  try {
    sessionStorage.setItem(TOKEN_KEY, given);
  } catch {
    /* no storage: the token lasts as long as the page */
  }
  url.searchParams.delete('token');
  history.replaceState(history.state, '', `${url.pathname}${url.search}${url.hash}`);
  return given;
}

const token = takeToken();

/** The headers of an API request: the token, and for a POST its JSON body's type (the
 * server refuses a POST without it). */
function headers(post: boolean): Record<string, string> {
  const h: Record<string, string> = {};
  if (token) h[TOKEN_HEADER] = token;
  if (post) h['Content-Type'] = 'application/json';
  return h;
}

/** fetch() of an API path with the token; a network failure becomes an ApiError. */
async function send(path: string, method: 'GET' | 'POST', body?: unknown): Promise<Response> {
  try {
    return await fetch(path, {
      method,
      headers: headers(method === 'POST'),
      body: method === 'POST' ? JSON.stringify(body ?? {}) : undefined,
    });
  } catch (e) {
    throw new ApiError(0, `the studio server does not answer (${(e as Error).message})`);
  }
}

async function request<T>(method: 'GET' | 'POST', path: string, body?: unknown): Promise<T> {
  const res = await send(path, method, body);
  if (!res.ok) throw await failure(res);
  return (await res.json()) as T;
}

/** The parameters of a mesh request (GET /api/mesh, an edit with its mesh). */
function meshQuery(options: MeshOptions): URLSearchParams {
  const query = solverQuery(options);
  if (options.base) query.set('base', String(options.base));
  if (options.resolution) query.set('resolution', String(options.resolution));
  return query;
}

/** The solver parameters of a request that solves (mesh, boundaries). */
function solverQuery(options: Pick<MeshOptions, 'solver' | 'seed'>): URLSearchParams {
  const query = new URLSearchParams();
  if (options.solver) query.set('solver', options.solver);
  if (options.seed !== undefined) query.set('seed', String(options.seed));
  return query;
}

export const api = {
  model: () => request<ModelState>('GET', '/api/model'),
  edit: (edit: Edit) => request<Status>('POST', '/api/edit', edit),
  endGroup: () => request<Status>('POST', '/api/end-group'),
  transform: (t: Transform) => request<Status>('POST', '/api/transform', t),
  undo: () => request<Status>('POST', '/api/undo'),
  redo: () => request<Status>('POST', '/api/redo'),
  files: async () => (await request<{ files: string[] }>('GET', '/api/files')).files,
  open: (path: string) => request<FileStatus>('POST', '/api/open', { path }),
  save: () => request<FileStatus>('POST', '/api/save'),
  saveAs: (path: string) => request<FileStatus>('POST', '/api/save-as', { path }),
  exportFile: (path: string, resolution?: number) =>
    request<ExportResult>('POST', '/api/export', resolution ? { path, resolution } : { path }),
  newModel: (m: NewModel) => request<FileStatus>('POST', '/api/new', m),
  recover: () => request<Status>('POST', '/api/recover'),
  discardRecovery: () => request<Status>('POST', '/api/discard-recovery'),

  /** The true boundary curves of every patch: float32 [patch][4 sides][samples][xyz]. */
  async boundaries(
    samples: number,
    solver: Pick<MeshOptions, 'solver' | 'seed'> = {},
  ): Promise<{ revision: number; samples: number; xyz: Float32Array }> {
    const query = solverQuery(solver);
    query.set('samples', String(samples));
    const res = await send(`/api/boundaries?${query}`, 'GET');
    if (!res.ok) throw await failure(res);
    const buffer = await res.arrayBuffer();
    if (buffer.byteLength % (48 * samples) !== 0)
      throw new ApiError(0, `boundaries: ${buffer.byteLength} bytes, not whole patches of ${samples} samples a side`);
    return { revision: Number(res.headers.get('X-Revision')), samples, xyz: new Float32Array(buffer) };
  },

  /** The frame of every triangle of the mesh at `resolution`. */
  async patchIds(resolution: number): Promise<{ revision: number; ids: Uint32Array }> {
    const res = await send(`/api/patch-ids?resolution=${resolution}`, 'GET');
    if (!res.ok) throw await failure(res);
    return { revision: Number(res.headers.get('X-Revision')), ids: new Uint32Array(await res.arrayBuffer()) };
  },

  /** The parameters (u, v) of the points of frame `frame`'s patch nearest `points`. */
  patchUv: async (frame: number, points: Vec3[], solver: Pick<MeshOptions, 'solver' | 'seed'> = {}) =>
    (await request<{ uv: [number, number][] }>('POST', `/api/patch-uv?${solverQuery(solver)}`, { frame, points })).uv,
  /** The points S(u, v) of frame `frame`'s patch. */
  patchPoints: async (frame: number, uv: (readonly [number, number])[], solver: Pick<MeshOptions, 'solver' | 'seed'> = {}) =>
    (await request<{ points: Vec3[] }>('POST', `/api/patch-points?${solverQuery(solver)}`, { frame, uv })).points,

  async mesh(options: MeshOptions = {}): Promise<MeshData | MeshDelta> {
    const q = meshQuery(options).toString();
    const res = await send(`/api/mesh${q ? `?${q}` : ''}`, 'GET');
    if (!res.ok) throw await failure(res);
    return parseMesh(await res.arrayBuffer(), res.headers);
  },

  /** The analytic mean and Gaussian curvature at every vertex of the mesh of `options`
   * (vertex frames): [H0, K0, H1, K1, ...], and the revision they are of. */
  async curvature(options: MeshOptions): Promise<{ revision: number; values: Float32Array }> {
    const res = await send(`/api/curvature?${meshQuery(options)}`, 'GET');
    if (!res.ok) throw await failure(res);
    const buffer = await res.arrayBuffer();
    if (buffer.byteLength % 8 !== 0) throw new ApiError(0, `curvature: ${buffer.byteLength} bytes, not pairs of float32`);
    return { revision: Number(res.headers.get('X-Revision')), values: new Float32Array(buffer) };
  },

  /** An edit answered with the mesh after it (POST /api/edit?mesh=1): one round trip. */
  async editWithMesh(edit: Edit, options: MeshOptions): Promise<{ value: Status; mesh: MeshData | MeshDelta }> {
    const query = meshQuery(options);
    query.set('mesh', '1');
    const res = await send(`/api/edit?${query}`, 'POST', edit);
    if (!res.ok) throw await failure(res);
    const status = res.headers.get('X-Status');
    if (!status) throw new ApiError(0, 'edit: the answer has no X-Status');
    return { value: JSON.parse(status) as Status, mesh: parseMesh(await res.arrayBuffer(), res.headers) };
  },
};

export type Api = typeof api;
