// The edit pump: sends the page's edits to the server one at a time, in order, coalescing a
// gesture's moves. No DOM and no page state here: what it sends through and whom it tells
// are given (web/test/pump.test.ts drives it with a fake server).
import type { Edit, Status } from './api';

/** What the pump sends through and reports to. */
export interface PumpPort {
  edit(edit: Edit): Promise<Status>;
  endGroup(): Promise<Status>;
  /** The server's status after an edit (`edited`) or the end of a group. */
  answered(status: Status, edited: boolean): void;
  /** The server refused an edit (it kept its model): show why and reload. */
  refused(error: unknown): Promise<void>;
}

type Operation = { kind: 'edit'; group: string; make: () => Edit } | { kind: 'end-group' };

/** A gesture (drag, slider) is a group: while an edit is in flight, only the latest next
 * edit of the group is kept; its end closes the group (POST /api/end-group) after its last
 * edit. Edits outside a group are each their own undo step. */
export class EditPump {
  private group = '';
  private queue: Operation[] = [];
  private busy = false;
  private waiters: (() => void)[] = [];
  private counter = 0;

  constructor(private readonly port: PumpPort) {}

  /** Starts a gesture (ending one still open): its edits share one undo group. */
  begin(kind: string): void {
    if (this.group) this.queue.push({ kind: 'end-group' });
    this.group = `${kind}-${Date.now().toString(36)}-${++this.counter}`;
  }

  /** Whether a gesture is open. */
  get active(): boolean {
    return this.group !== '';
  }

  /** Queues an edit; `make` runs when it is sent (so it sends the latest values). Within a
   * gesture, an edit still waiting is replaced by the next one. */
  push(make: () => Edit): void {
    const last = this.queue[this.queue.length - 1];
    if (last && last.kind === 'edit' && last.group === this.group && this.group) last.make = make;
    else this.queue.push({ kind: 'edit', group: this.group, make });
    if (!this.busy) void this.flush();
  }

  private async flush(): Promise<void> {
    this.busy = true;
    for (let op = this.queue.shift(); op; op = this.queue.shift()) {
      try {
        if (op.kind === 'end-group') {
          this.port.answered(await this.port.endGroup(), false);
          continue;
        }
        const edit = { ...op.make(), ...(op.group ? { group: op.group } : {}) } as Edit;
        this.port.answered(await this.port.edit(edit), true);
      } catch (e) {
        await this.port.refused(e);
      }
    }
    this.busy = false;
    for (const w of this.waiters.splice(0)) w();
  }

  /** Resolves when every queued operation is done. */
  idle(): Promise<void> {
    return this.busy || this.queue.length ? new Promise((r) => this.waiters.push(r)) : Promise.resolve();
  }

  /** Ends the gesture: its group closes after its last edit. Resolves when all is sent. */
  end(): Promise<void> {
    if (this.group) {
      this.group = '';
      this.queue.push({ kind: 'end-group' });
      if (!this.busy) void this.flush();
    }
    return this.idle();
  }

  /** One edit that is its own undo step. */
  once(kind: string, make: () => Edit): Promise<void> {
    this.begin(kind);
    this.push(make);
    return this.end();
  }
}
