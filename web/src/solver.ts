// The solver of the surface view: the global solver (the default: every strip's shared
// cubic minimises the residual of all its patches) or the seed's local one, where the seed
// frame's own a1 / a2 set its strips (docs/vertex-frames.md, "The two solvers"). The
// choice travels with every mesh request (GET /api/mesh?solver=local&seed=K); the model
// file is not changed.
import type { MeshOptions } from './api';
import { $ } from './dom';
import { parseNumber } from './input';
import type { Studio } from './studio';

export function mountSolver(studio: Studio): void {
  const local = $<HTMLInputElement>('local-solver');
  const seed = $<HTMLInputElement>('seed-frame');
  const frames = () => studio.store.state.model?.frames.length ?? 0;

  /** Reads the boxes into studio.solver; false (and the reason shown) when the seed is bad. */
  const apply = (): boolean => {
    seed.disabled = !local.checked;
    if (!local.checked) {
      studio.solver = {};
      seed.classList.remove('invalid');
      return true;
    }
    const n = frames();
    const parsed = parseNumber(seed.value, { label: 'seed frame', min: 0, max: Math.max(0, n - 1) });
    const error = 'error' in parsed ? parsed.error : Number.isInteger(parsed.value) ? '' : 'seed frame: a whole number';
    seed.classList.toggle('invalid', error !== '');
    if (error) {
      studio.showError(error);
      return false;
    }
    studio.solver = { solver: 'local', seed: (parsed as { value: number }).value } satisfies MeshOptions;
    return true;
  };
  local.addEventListener('change', () => {
    // Turned on with a frame selected: that frame is the seed.
    const selected = [...studio.store.state.selectedFrames];
    if (local.checked && selected.length) seed.value = String(Math.min(...selected));
    if (apply()) studio.modelChanged();
  });
  seed.addEventListener('change', () => {
    if (apply()) studio.modelChanged();
  });
  // Another model: its frames; a seed it does not have falls back to frame 0.
  studio.store.subscribe(['model'], () => {
    if (local.checked && Number(seed.value) >= frames()) {
      seed.value = '0';
      if (apply()) studio.modelChanged();
    }
  });
  apply();
}
