// Mesh sync: keeps the page's surface mesh at the server's latest revision. One request is
// in flight at a time; changes during it ask for one more after it. A mesh of the same
// resolution and triangles comes as a delta of the changed vertices, written into the
// page's mesh in place (only those vertices are re-uploaded to WebGL). No DOM here
// (web/test/mesh-sync.test.ts).
import type { MeshOptions } from './api';
import { applyDelta } from './wire';
import type { MeshData, MeshDelta } from './wire';

export interface MeshPort {
  mesh(options: MeshOptions): Promise<MeshData | MeshDelta>;
  /** The resolution to ask for now (a gesture may ask for a coarser preview). */
  resolution(): number;
  /** The page's mesh, which a delta updates. */
  current(): MeshData | null;
  /** A whole new mesh. */
  replaced(mesh: MeshData): void;
  /** The page's mesh, updated in place by `delta`. */
  updated(mesh: MeshData, delta: MeshDelta): void;
  failed(error: unknown): void;
}

export class MeshSync {
  private busy = false;
  private again = false;
  private waiters: (() => void)[] = [];

  constructor(private readonly port: MeshPort) {}

  /** Fetches the mesh of the server's current model (after the one in flight, if any). */
  async request(): Promise<void> {
    if (this.busy) {
      this.again = true;
      return this.idle();
    }
    this.busy = true;
    try {
      let whole = false; // after a delta that did not fit: ask for the whole mesh
      do {
        this.again = false;
        const resolution = this.port.resolution();
        const mesh = this.port.current();
        const base = !whole && mesh?.resolution === resolution ? mesh.id : undefined;
        whole = false;
        const answer = await this.port.mesh({ resolution, base });
        if (answer.kind === 'delta') {
          const have = this.port.current();
          if (!have || !applyDelta(have, answer)) {
            whole = this.again = true;
            continue;
          }
          this.port.updated(have, answer);
        } else {
          this.port.replaced(answer);
        }
        // The resolution wanted changed meanwhile (a gesture ended): fetch it.
        if (this.port.resolution() !== resolution) this.again = true;
      } while (this.again);
    } catch (e) {
      this.port.failed(e);
    } finally {
      this.busy = false;
      for (const w of this.waiters.splice(0)) w();
    }
  }

  /** Resolves when no request is in flight. */
  idle(): Promise<void> {
    return this.busy ? new Promise((r) => this.waiters.push(r)) : Promise.resolve();
  }
}
