// Mesh sync: one request in flight, one more after it when the model changed meanwhile,
// deltas against the mesh the page holds at that resolution (a preview's and the chosen
// resolution's), the whole mesh when a delta does not fit or names another base.
import { describe, expect, it } from 'vitest';
import type { MeshOptions } from '../src/api';
import { MESH_SLOTS, MeshSync } from '../src/mesh-sync';
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
  const state = {
    current: null as MeshData | null,
    resolution: 16,
    replaced: 0,
    updated: 0,
    dropped: [] as MeshData[],
    errors: [] as unknown[],
  };
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
    replaced: (m, dropped) => {
      state.current = m;
      ++state.replaced;
      if (dropped) state.dropped.push(dropped);
    },
    updated: (m) => ((state.current = m), ++state.updated),
    failed: (e) => state.errors.push(e),
  });
  const open = async () => {
    await new Promise((r) => setTimeout(r, 0));
    gates.shift()!();
    await new Promise((r) => setTimeout(r, 0));
  };
  /** One request answered at once: how the page comes to hold `m`. */
  const fetch = async () => {
    const done = sync.request();
    await open();
    await done;
  };
  return { sync, asked, state, open, fetch };
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
    const h = harness([() => mesh(1, 16), () => delta(1, 2, 16, 99), () => mesh(3, 16)]);
    await h.fetch();
    const done = h.sync.request();
    await h.open();
    await h.open();
    await done;
    expect(h.asked.slice(1)).toEqual([{ resolution: 16, base: 1 }, { resolution: 16, base: undefined }]);
    expect(h.state.current!.id).toBe(3);
    expect(h.state.dropped.map((m) => m.id)).toEqual([1]);
  });

  it('refuses a delta made against another mesh than the one it held, and asks for the whole', async () => {
    // The server answers with a delta against mesh 7, which the page never held.
    const h = harness([() => mesh(1, 16), () => delta(7, 2, 16), () => mesh(3, 16)]);
    await h.fetch();
    const before = Array.from(h.state.current!.positions);
    const done = h.sync.request();
    await h.open();
    expect(Array.from(h.sync.heldAt(16)!.positions)).toEqual(before); // nothing written
    await h.open();
    await done;
    expect(h.asked.slice(1)).toEqual([{ resolution: 16, base: 1 }, { resolution: 16, base: undefined }]);
    expect([h.state.current!.id, h.state.updated]).toEqual([3, 0]);
  });

  it('keeps the chosen resolution while a preview is shown: the release is a delta against it', async () => {
    const h = harness([
      () => mesh(1, 16),
      () => mesh(2, 4), // the gesture's first preview: whole
      (o) => delta(o.base!, 3, 4), // its next: a delta against the preview
      (o) => delta(o.base!, 4, 16), // the release: a delta against the full mesh 1
    ]);
    await h.fetch();
    const full = h.state.current!;
    h.state.resolution = 4;
    await h.fetch();
    await h.fetch();
    h.state.resolution = 16;
    await h.fetch();
    expect(h.asked.map((o) => o.base)).toEqual([undefined, undefined, 2, 1]);
    expect(h.state.current).toBe(full); // the same arrays (and WebGL buffers), updated in place
    expect([full.id, h.state.replaced, h.state.updated, h.state.dropped.length]).toEqual([4, 2, 2, 0]);
    expect(h.sync.heldAt(4)!.id).toBe(3);
  });

  it('holds at most MESH_SLOTS resolutions, dropping the least recently shown', async () => {
    const h = harness([() => mesh(1, 16), () => mesh(2, 4), () => mesh(3, 8)]);
    for (const resolution of [16, 4, 8]) {
      h.state.resolution = resolution;
      await h.fetch();
    }
    expect(MESH_SLOTS).toBe(2);
    expect(h.state.dropped.map((m) => m.id)).toEqual([1]);
    expect([h.sync.heldAt(16), h.sync.heldAt(4)?.id, h.sync.heldAt(8)?.id]).toEqual([null, 2, 3]);
  });

  it('asks for the whole mesh at another resolution, and again when the wanted one changed in flight', async () => {
    const h = harness([() => mesh(1, 16), () => mesh(2, 4), (o) => delta(o.base!, 3, 16)]);
    await h.fetch();
    h.state.resolution = 4; // a gesture's preview
    const done = h.sync.request();
    h.state.resolution = 16; // the gesture ended while the preview was in flight
    await h.open();
    await h.open();
    await done;
    expect(h.asked.slice(1)).toEqual([{ resolution: 4, base: undefined }, { resolution: 16, base: 1 }]);
    expect(h.state.current!.resolution).toBe(16);
  });

  it('takes the mesh an edit brings (one round trip), unless a mesh request is in flight', async () => {
    const h = harness([() => mesh(1, 16), (o) => delta(o.base!, 2, 16)]);
    await h.fetch();
    const sent: MeshOptions[] = [];
    const value = await h.sync.along(async (o) => {
      sent.push(o);
      return { value: 'status', mesh: delta(o.base!, 5, 16) };
    });
    expect(value).toBe('status');
    expect(sent).toEqual([{ resolution: 16, base: 1 }]);
    expect([h.state.current!.id, h.state.updated]).toEqual([5, 1]);
    expect(Array.from(h.state.current!.positions.subarray(3, 6))).toEqual([7, 8, 9]);

    const inFlight = h.sync.request();
    expect(await h.sync.along(async () => ({ value: 'x', mesh: mesh(9, 16) }))).toBeNull();
    await h.open();
    await inFlight;
    expect(h.asked.map((o) => o.base)).toEqual([undefined, 5]);
  });

  it('asks for the whole mesh after an edit whose mesh does not fit', async () => {
    const h = harness([() => mesh(1, 16), () => mesh(3, 16)]);
    await h.fetch();
    const done = h.sync.along(async () => ({ value: 0, mesh: delta(7, 2, 16) }));
    await done;
    await h.open();
    await h.sync.idle();
    expect(h.asked.slice(1)).toEqual([{ resolution: 16, base: undefined }]);
    expect(h.state.current!.id).toBe(3);
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
