// Mesh sync: keeps the page's surface mesh at the server's latest revision. One request is
// in flight at a time; changes during it ask for one more after it. The page holds the last
// mesh of each of MESH_SLOTS resolutions (a gesture's preview and the chosen resolution, as
// the server does: apps/studio/README.md); a mesh of a resolution the page holds comes as a
// delta of the vertices changed since that mesh, written into it in place (only those
// vertices are re-uploaded to WebGL), so the end of a gesture needs no whole mesh. A delta
// names its base mesh; one that does not fit the mesh held is refused and the whole mesh
// asked for. No DOM here (web/test/mesh-sync.test.ts).
import type { MeshOptions } from './api';
import { applyDelta } from './wire';
import type { MeshData, MeshDelta } from './wire';

/** Resolutions whose last mesh the page keeps (the server keeps as many delta bases). */
export const MESH_SLOTS = 2;

export interface MeshPort {
  mesh(options: MeshOptions): Promise<MeshData | MeshDelta>;
  /** The resolution to ask for now (a gesture may ask for a coarser preview). */
  resolution(): number;
  /** A whole new mesh, to show; `dropped`: a mesh the page no longer holds (free it). */
  replaced(mesh: MeshData, dropped: MeshData | null): void;
  /** A held mesh, updated in place by `delta`, to show (it may not be the one shown). */
  updated(mesh: MeshData, delta: MeshDelta): void;
  failed(error: unknown): void;
}

export class MeshSync {
  private busy = false;
  private again = false;
  private waiters: (() => void)[] = [];
  /** The meshes the page holds, the most recently shown first. */
  private held: MeshData[] = [];

  constructor(private readonly port: MeshPort) {}

  /** The mesh the page holds at `resolution`, if any. */
  heldAt(resolution: number): MeshData | null {
    return this.held.find((m) => m.resolution === resolution) ?? null;
  }

  /** Takes `mesh` as the most recent; returns the mesh it displaces, if any. */
  private hold(mesh: MeshData): MeshData | null {
    const same = this.held.findIndex((m) => m.resolution === mesh.resolution || m === mesh);
    let dropped: MeshData | null = null;
    if (same >= 0) {
      const [old] = this.held.splice(same, 1);
      if (old !== mesh) dropped = old;
    } else if (this.held.length >= MESH_SLOTS) {
      dropped = this.held.pop()!;
    }
    this.held.unshift(mesh);
    return dropped;
  }

  /** Takes a mesh answer at `resolution`: false when it is a delta that does not fit the
   * mesh it names (the whole mesh is then to be asked for). */
  private take(answer: MeshData | MeshDelta): boolean {
    if (answer.kind === 'full') {
      this.port.replaced(answer, this.hold(answer));
      return true;
    }
    const have = this.held.find((m) => m.id === answer.base);
    if (!have || !applyDelta(have, answer)) return false;
    this.hold(have);
    this.port.updated(have, answer);
    return true;
  }

  /** Fetches the mesh of the server's current model (after the one in flight, if any). */
  async request(whole = false): Promise<void> {
    if (this.busy) {
      this.again = true;
      return this.idle();
    }
    this.busy = true;
    try {
      do {
        this.again = false;
        const resolution = this.port.resolution();
        const base = whole ? undefined : this.heldAt(resolution)?.id;
        // after a delta that did not fit: ask for the whole mesh
        whole = !this.take(await this.port.mesh({ resolution, base }));
        // The resolution wanted changed meanwhile (a gesture ended): fetch it.
        if (whole || this.port.resolution() !== resolution) this.again = true;
      } while (this.again);
    } catch (e) {
      this.port.failed(e);
    } finally {
      this.finish();
    }
  }

  /** Sends a request that carries a mesh with its answer (an edit with the mesh after it:
   * one round trip instead of two) and takes that mesh; null, and nothing sent, while a
   * mesh request is in flight (send the request alone: the mesh follows). A failure of
   * `send` is its caller's. */
  async along<T>(send: (options: MeshOptions) => Promise<{ value: T; mesh: MeshData | MeshDelta }>): Promise<T | null> {
    if (this.busy) return null;
    this.busy = true;
    let whole = false;
    try {
      const resolution = this.port.resolution();
      const answer = await send({ resolution, base: this.heldAt(resolution)?.id });
      whole = !this.take(answer.mesh);
      if (whole || this.port.resolution() !== resolution) this.again = true;
      return answer.value;
    } finally {
      this.finish(whole);
    }
  }

  /** The end of a request: another when one was asked for meanwhile, else the waiters. */
  private finish(whole = false): void {
    this.busy = false;
    if (this.again) {
      this.again = false;
      void this.request(whole);
      return;
    }
    for (const w of this.waiters.splice(0)) w();
  }

  /** Resolves when no request is in flight. */
  idle(): Promise<void> {
    return this.busy ? new Promise((r) => this.waiters.push(r)) : Promise.resolve();
  }
}
