// The typed client of the studio server's API (apps/studio/README.md). Every request of
// the front-end goes through this module, and carries the studio's per-launch token.

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
/** What the frame view draws of a view-only (spectral, cross-sections) model. */
export interface ModelView {
  /** Position curves of the conditions, closed, sampled around v. */
  curves: Vec3[][];
  /** The spine A0(u) of each patch. */
  spines: Vec3[][];
}

export interface ModelState extends Status {
  path: string;
  recovery: boolean;
  /** False for models the studio shows but does not edit (spectral, cross-sections). */
  editable: boolean;
  /** The model as its file says (a vertex-frames Model when editable). */
  model: Model;
  view?: ModelView;
}
export interface FileStatus extends Status {
  path: string;
  recovery?: boolean;
}
export interface ExportResult {
  path: string;
  vertices: number;
  triangles: number;
}

export type Edit =
  | { op: 'move-vertex'; vertex: number; position: Vec3; group?: string }
  | { op: 'set-parameters'; frames: number[]; a1?: Vec3; a2?: Vec3; group?: string }
  | { op: 'set-forces'; frame: number; forces: FrameForce[]; group?: string }
  | { op: 'set-shared-forces'; forces: SharedForce[]; group?: string };

/** A whole-model transform (POST /api/transform), of any model type: scale about
 * `center`, then rotate (about its own center, else `center`), then translate. */
export interface Transform {
  translate?: Vec3;
  rotate?: { axis: Vec3; degrees: number; center?: Vec3 };
  scale?: number;
  center?: Vec3;
}

/** The surface as the server streams it (GET /api/mesh). */
export interface MeshData {
  kind: 'full';
  /** The server's id of this mesh (X-Mesh-Id): the `base` of the next request. */
  id: number;
  vertexCount: number;
  triangleCount: number;
  /** The low 32 bits of the revision the mesh was made from. */
  revision: number;
  resolution: number;
  positions: Float32Array;
  normals: Float32Array;
  indices: Uint32Array;
  solveMs: number;
  tessellateMs: number;
  c0Gap: number;
}

/** Only what changed since the client's mesh `base` (same triangles): the changed vertex
 * runs (start, count) and their positions and normals, in run order. */
export interface MeshDelta {
  kind: 'delta';
  base: number;
  id: number;
  vertexCount: number;
  triangleCount: number;
  revision: number;
  resolution: number;
  runs: Uint32Array;
  positions: Float32Array;
  normals: Float32Array;
  solveMs: number;
  tessellateMs: number;
  c0Gap: number;
}

export interface MeshOptions {
  /** The id of the mesh the client has: the server may answer with a delta against it. */
  base?: number;
  resolution?: number;
  solver?: 'global' | 'local';
  seed?: number;
}

/** A request the server refused: its status and the message of {"error": ...}. */
export class ApiError extends Error {
  constructor(
    readonly status: number,
    message: string,
  ) {
    super(message);
    this.name = 'ApiError';
  }
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

/** Parses the binary mesh: four uint32 (V, T, revision, resolution), positions, normals,
 * indices; or, when the answer has X-Mesh-Base, a delta: five uint32 (V, T, revision,
 * resolution, run count R), runs uint32[2R], then the changed vertices' positions and
 * normals. */
export function parseMesh(buffer: ArrayBuffer, headers?: Headers): MeshData | MeshDelta {
  const number = (name: string) => {
    const text = headers?.get(name);
    return text == null ? NaN : Number(text);
  };
  const common = {
    id: number('X-Mesh-Id'),
    solveMs: number('X-Solve-Ms'),
    tessellateMs: number('X-Tessellate-Ms'),
    c0Gap: number('X-C0-Gap'),
  };
  const base = number('X-Mesh-Base');
  if (Number.isFinite(base)) {
    if (buffer.byteLength < 20) throw new ApiError(0, 'mesh delta: truncated header');
    const header = new DataView(buffer, 0, 20);
    const r = header.getUint32(16, true);
    if (buffer.byteLength < 20 + 8 * r) throw new ApiError(0, 'mesh delta: truncated runs');
    const runs = new Uint32Array(buffer, 20, 2 * r);
    let changed = 0;
    for (let k = 1; k < runs.length; k += 2) changed += runs[k];
    const expected = 20 + 8 * r + 24 * changed;
    if (buffer.byteLength !== expected)
      throw new ApiError(0, `mesh delta: ${buffer.byteLength} bytes, expected ${expected}`);
    return {
      kind: 'delta',
      base,
      vertexCount: header.getUint32(0, true),
      triangleCount: header.getUint32(4, true),
      revision: header.getUint32(8, true),
      resolution: header.getUint32(12, true),
      runs,
      positions: new Float32Array(buffer, 20 + 8 * r, 3 * changed),
      normals: new Float32Array(buffer, 20 + 8 * r + 12 * changed, 3 * changed),
      ...common,
    };
  }
  if (buffer.byteLength < 16) throw new ApiError(0, 'mesh: truncated header');
  const header = new DataView(buffer, 0, 16);
  const v = header.getUint32(0, true);
  const t = header.getUint32(4, true);
  const expected = 16 + 4 * (6 * v + 3 * t);
  if (buffer.byteLength !== expected)
    throw new ApiError(0, `mesh: ${buffer.byteLength} bytes, expected ${expected}`);
  return {
    kind: 'full',
    vertexCount: v,
    triangleCount: t,
    revision: header.getUint32(8, true),
    resolution: header.getUint32(12, true),
    positions: new Float32Array(buffer, 16, 3 * v),
    normals: new Float32Array(buffer, 16 + 12 * v, 3 * v),
    indices: new Uint32Array(buffer, 16 + 24 * v, 3 * t),
    ...common,
  };
}

/** Writes a delta into the mesh it was made against (in place); false when it does not fit
 * (another base or other counts: fetch the whole mesh instead). */
export function applyDelta(mesh: MeshData, delta: MeshDelta): boolean {
  if (delta.base !== mesh.id || delta.vertexCount !== mesh.vertexCount || delta.triangleCount !== mesh.triangleCount)
    return false;
  let k = 0;
  for (let r = 0; r < delta.runs.length; r += 2) {
    const start = 3 * delta.runs[r];
    const n = 3 * delta.runs[r + 1];
    if (start + n > mesh.positions.length) return false;
    mesh.positions.set(delta.positions.subarray(k, k + n), start);
    mesh.normals.set(delta.normals.subarray(k, k + n), start);
    k += n;
  }
  Object.assign(mesh, {
    id: delta.id,
    revision: delta.revision,
    resolution: delta.resolution,
    solveMs: delta.solveMs,
    tessellateMs: delta.tessellateMs,
    c0Gap: delta.c0Gap,
  });
  return true;
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
  exportMesh: (path: string, resolution?: number) =>
    request<ExportResult>('POST', '/api/export', resolution ? { path, resolution } : { path }),
  recover: () => request<Status>('POST', '/api/recover'),
  discardRecovery: () => request<Status>('POST', '/api/discard-recovery'),

  async mesh(options: MeshOptions = {}): Promise<MeshData | MeshDelta> {
    const query = new URLSearchParams();
    if (options.base) query.set('base', String(options.base));
    if (options.resolution) query.set('resolution', String(options.resolution));
    if (options.solver) query.set('solver', options.solver);
    if (options.seed !== undefined) query.set('seed', String(options.seed));
    const q = query.toString();
    const res = await send(`/api/mesh${q ? `?${q}` : ''}`, 'GET');
    if (!res.ok) throw await failure(res);
    return parseMesh(await res.arrayBuffer(), res.headers);
  },
};

export type Api = typeof api;
