// Mesh sync: one request in flight, one more after it when the model changed meanwhile,
// deltas against the page's mesh, the whole mesh when a delta does not fit.
import { describe, expect, it } from 'vitest';
import type { MeshOptions } from '../src/api';
import { MeshSync } from '../src/mesh-sync';
import type { MeshData, MeshDelta } from '../src/wire';

function mesh(id: number, resolution: number): MeshData {
  return {
    kind: 'full', id, vertexCount: 2, triangleCount: 0, revision: id, resolution,
    positions: new Float32Array(6), normals: new Float32Array(6), indices: new Uint32Array(0),
    solveMs: 0, tessellateMs: 0, c0Gap: 0,
  };
}
function delta(base: number, id: number, resolution: number, vertexCount = 2): MeshDelta {
  return {
    kind: 'delta', base, id, vertexCount, triangleCount: 0, revision: id, resolution,
    runs: new Uint32Array([1, 1]), positions: new Float32Array([7, 8, 9]), normals: new Float32Array(3),
    solveMs: 0, tessellateMs: 0, c0Gap: 0,
  };
}

function harness(answers: ((o: MeshOptions) => MeshData | MeshDelta)[]) {
  const asked: MeshOptions[] = [];
  const state = { current: null as MeshData | null, resolution: 16, replaced: 0, updated: 0, errors: [] as unknown[] };
  const gates: (() => void)[] = [];
  const sync = new MeshSync({
    mesh: async (o) => {
      asked.push(o);
      await new Promise<void>((r) => gates.push(r));
      const next = answers.shift();
      if (!next) throw new Error('no answer');
      return next(o);
    },
    resolution: () => state.resolution,
    current: () => state.current,
    replaced: (m) => ((state.current = m), ++state.replaced),
    updated: () => ++state.updated,
    failed: (e) => state.errors.push(e),
  });
  const open = async () => {
    await new Promise((r) => setTimeout(r, 0));
    gates.shift()!();
    await new Promise((r) => setTimeout(r, 0));
  };
  return { sync, asked, state, open };
}

describe('MeshSync', () => {
  it('asks again once after the request in flight when the model changed meanwhile', async () => {
    const h = harness([() => mesh(1, 16), (o) => delta(o.base!, 2, 16)]);
    const first = h.sync.request();
    const second = h.sync.request(); // while the first is in flight
    const third = h.sync.request();
    await h.open();
    await h.open();
    await Promise.all([first, second, third]);
    expect(h.asked).toEqual([{ resolution: 16, base: undefined }, { resolution: 16, base: 1 }]);
    expect([h.state.replaced, h.state.updated]).toEqual([1, 1]);
    expect(Array.from(h.state.current!.positions.subarray(3, 6))).toEqual([7, 8, 9]);
  });

  it('fetches the whole mesh when a delta does not fit the page mesh', async () => {
    const h = harness([() => delta(1, 2, 16, 99), () => mesh(3, 16)]);
    h.state.current = mesh(1, 16);
    const done = h.sync.request();
    await h.open();
    await h.open();
    await done;
    expect(h.asked).toEqual([{ resolution: 16, base: 1 }, { resolution: 16, base: undefined }]);
    expect(h.state.current!.id).toBe(3);
  });

  it('asks for the whole mesh at another resolution, and again when the wanted one changed in flight', async () => {
    const h = harness([() => mesh(2, 4), () => mesh(3, 16)]);
    h.state.current = mesh(1, 16);
    h.state.resolution = 4; // a gesture's preview
    const done = h.sync.request();
    h.state.resolution = 16; // the gesture ended while the preview was in flight
    await h.open();
    await h.open();
    await done;
    expect(h.asked).toEqual([{ resolution: 4, base: undefined }, { resolution: 16, base: undefined }]);
    expect(h.state.current!.resolution).toBe(16);
  });

  it('reports a failure and is ready for the next request', async () => {
    const h = harness([]);
    const done = h.sync.request();
    await h.open();
    await done;
    expect(h.state.errors).toHaveLength(1);
    await h.sync.idle();
  });
});
