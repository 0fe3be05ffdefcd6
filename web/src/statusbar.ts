// The status line, the error line, the file name with its unsaved mark, and the undo and
// redo buttons' states: all from the store.
import { $, plural } from './dom';
import type { Studio } from './studio';

function formatGap(gap: number): string {
  if (!Number.isFinite(gap)) return '?';
  return gap === 0 ? '0' : gap.toExponential(2);
}

export function mountStatusBar(studio: Studio): void {
  studio.store.subscribe(['model', 'status', 'mesh'], (state) => {
    const m = state.model;
    const parts: string[] = [];
    if (m) parts.push(plural(m.frames.length, 'frame'), plural(m.vertices.length, 'vertex').replace('vertexs', 'vertices'));
    if (state.status) parts.push(`rev ${state.status.revision}`, `undo ${state.status.undo}`, `redo ${state.status.redo}`);
    if (state.mesh) {
      parts.push(`solve ${state.mesh.solveMs.toFixed(2)} ms`, `tessellate ${state.mesh.tessellateMs.toFixed(2)} ms`);
      parts.push(`${plural(state.mesh.triangleCount, 'triangle')}`);
    }
    if (!state.hasEditableParts) parts.push(`${state.modelType} model: drag its handles (Transform moves it whole)`);
    if (state.meshStale) parts.push('surface out of date (Create)');
    if (state.message) parts.push(state.message);
    $('status').textContent = parts.join(' · ');
    $('error').textContent = state.error;
    $('model-path').textContent = state.path;
    $('dirty').hidden = !state.status?.dirty;
    $<HTMLButtonElement>('undo').disabled = !state.status || state.status.undo === 0;
    $<HTMLButtonElement>('redo').disabled = !state.status || state.status.redo === 0;
    $('recovery').hidden = !state.recovery;
    $('surface-view').classList.toggle('surface-stale', state.meshStale);
    $('c0-gap').textContent = state.mesh ? `C0 gap ${formatGap(state.mesh.c0Gap)}` : '';
  });
}
