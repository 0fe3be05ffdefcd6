// The mesh wire format of GET /api/mesh (apps/studio/README.md): the whole mesh or a delta
// against the client's last one, parsed without copying, and a delta written into its mesh.
// No DOM here: the unit tests (web/test) run it in Node.

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

