// The edit pump: one edit in flight, a gesture's moves coalesced to the latest, groups
// closed after their last edit, single edits never merged, refusals reported.
import { describe, expect, it } from 'vitest';
import type { Edit, Status } from '../src/api';
import { EditPump } from '../src/pump';

/** A fake server whose answers the test releases one at a time. */
function fakeServer() {
  const sent: (Edit | 'end-group')[] = [];
  const pending: { resolve: (s: Status) => void; reject: (e: unknown) => void }[] = [];
  const refused: unknown[] = [];
  let revision = 0;
  const answer = () =>
    new Promise<Status>((resolve, reject) => pending.push({ resolve, reject }));
  const pump = new EditPump({
    edit: (edit) => (sent.push(edit), answer()),
    endGroup: () => (sent.push('end-group'), answer()),
    answered: () => {},
    refused: async (e) => void refused.push(e),
  });
  const tick = () => new Promise((r) => setTimeout(r, 0));
  return {
    pump,
    sent,
    refused,
    /** Answers the oldest request (or refuses it), then lets the pump go on. */
    async release(fail = false) {
      const p = pending.shift();
      if (!p) throw new Error('nothing in flight');
      if (fail) p.reject(new Error('refused'));
      else p.resolve({ revision: ++revision, undo: 0, redo: 0, dirty: true });
      await tick();
    },
    inFlight: () => pending.length,
  };
}

const move = (x: number): Edit => ({ op: 'move-vertex', vertex: 0, position: [x, 0, 0] });
const positions = (sent: (Edit | 'end-group')[]) =>
  sent.map((e) => (e === 'end-group' ? 'end' : (e as { position: number[] }).position[0]));

describe('EditPump', () => {
  it('sends one edit at a time and keeps only the latest move of a gesture', async () => {
    const s = fakeServer();
    s.pump.begin('drag');
    for (let x = 1; x <= 5; ++x) s.pump.push(() => move(x));
    expect(s.inFlight()).toBe(1);
    expect(positions(s.sent)).toEqual([1]); // 2, 3, 4 were replaced by 5 while 1 was in flight
    const done = s.pump.end();
    await s.release();
    expect(positions(s.sent)).toEqual([1, 5]);
    await s.release();
    expect(positions(s.sent)).toEqual([1, 5, 'end']);
    await s.release();
    await done;
    expect(s.inFlight()).toBe(0);
    // Every edit of the gesture carries the same group.
    const groups = new Set(s.sent.filter((e) => e !== 'end-group').map((e) => (e as Edit).group));
    expect(groups.size).toBe(1);
    expect([...groups][0]).toMatch(/^drag-/);
  });

  it('asks for the edit when it sends it (the latest value)', async () => {
    const s = fakeServer();
    let x = 1;
    s.pump.begin('slider');
    s.pump.push(() => move(x));
    s.pump.push(() => move(x));
    x = 9; // changed after the push, before the second edit is sent
    await s.release();
    expect(positions(s.sent)).toEqual([1, 9]);
  });

  it('never merges edits that are each their own undo step', async () => {
    const s = fakeServer();
    const a = s.pump.once('vertex', () => move(1));
    const b = s.pump.once('vertex', () => move(2));
    while (s.inFlight()) await s.release();
    await Promise.all([a, b]);
    expect(positions(s.sent)).toEqual([1, 'end', 2, 'end']);
    const [g1, g2] = [s.sent[0], s.sent[2]].map((e) => (e as Edit).group);
    expect(g1).not.toBe(g2);
  });

  it('reports a refused edit and goes on with the next', async () => {
    const s = fakeServer();
    const done = s.pump.once('vertex', () => move(1));
    await s.release(true);
    expect(s.refused).toHaveLength(1);
    await s.release();
    await done;
    expect(positions(s.sent)).toEqual([1, 'end']);
  });

  it('closes an open gesture when the next begins', async () => {
    const s = fakeServer();
    s.pump.begin('a');
    s.pump.push(() => move(1));
    s.pump.begin('b');
    s.pump.push(() => move(2));
    const done = s.pump.end();
    while (s.inFlight()) await s.release();
    await done;
    expect(positions(s.sent)).toEqual([1, 'end', 2, 'end']);
    expect((s.sent[0] as Edit).group).not.toBe((s.sent[2] as Edit).group);
  });
});
