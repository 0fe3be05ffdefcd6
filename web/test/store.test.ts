// The store: writes name their topics; each renderer runs once per batch, only for its
// topics; a write with no topic redraws nothing.
import { describe, expect, it } from 'vitest';
import { Store } from '../src/store';

describe('Store', () => {
  it('runs each subscriber once per batch of changes to its topics', async () => {
    const store = new Store();
    const calls: string[] = [];
    store.subscribe(['status'], () => calls.push('status'));
    store.subscribe(['selection', 'model'], (_, topics) => calls.push(`scene:${[...topics].sort().join('+')}`));
    store.update(['status'], (s) => (s.message = 'a'));
    store.update(['status'], (s) => (s.error = 'b'));
    store.update(['selection'], (s) => (s.selectedVertex = 3));
    expect(calls).toEqual([]); // nothing runs inside the writes
    await Promise.resolve();
    expect(calls).toEqual(['status', 'scene:selection+status']);
    expect(store.state.selectedVertex).toBe(3);
    expect(store.state.message).toBe('a');
  });

  it('a write with no topic changes the state and redraws nothing', async () => {
    const store = new Store();
    let runs = 0;
    store.subscribe(['model', 'selection', 'forces', 'mesh', 'status', 'vertex'], () => ++runs);
    store.update([], (s) => (s.message = 'quiet'));
    await Promise.resolve();
    expect(runs).toBe(0);
    expect(store.state.message).toBe('quiet');
  });

  it('unsubscribes', async () => {
    const store = new Store();
    let runs = 0;
    const off = store.subscribe(['mesh'], () => ++runs);
    off();
    store.update(['mesh'], (s) => (s.meshStale = true));
    await Promise.resolve();
    expect(runs).toBe(0);
  });
});
