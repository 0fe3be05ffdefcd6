// The Transform panel: move, rotate or scale the whole model, of any type, one undo step
// each; the views follow the model.
import { api } from './api';
import type { Transform, Vec3 } from './api';
import { $, readNumber } from './dom';
import type { NumberRule } from './input';
import { modelBox } from './viewport';
import type { Studio } from './studio';

/** The bounding box of a mesh's positions (null when empty). */
export function positionsBox(p: ArrayLike<number> | undefined): { min: Vec3; max: Vec3 } | null {
  if (!p || p.length < 3) return null;
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3)
    for (let c = 0; c < 3; ++c) {
      min[c] = Math.min(min[c], p[i + c]);
      max[c] = Math.max(max[c], p[i + c]);
    }
  return { min, max };
}

export function mountTransform(studio: Studio): void {
  const { store } = studio;

  /** Where rotations and scaling pivot: the centre of the surface's bounding box (of the
   * vertices while there is no mesh yet). */
  function modelCenter(): Vec3 {
    const box = positionsBox(store.state.mesh?.positions);
    if (box) return [0, 1, 2].map((c) => (box.min[c] + box.max[c]) / 2) as Vec3;
    if (store.state.model) {
      const b = modelBox(store.state.model);
      return [(b.min.x + b.max.x) / 2, (b.min.y + b.max.y) / 2, (b.min.z + b.max.z) / 2];
    }
    return [0, 0, 0];
  }

  /** The number in box `id`; throws (the action stops, its message shown) when none. */
  function numberOf(id: string, rule: NumberRule = {}): number {
    let message = '';
    const value = readNumber($<HTMLInputElement>(id), rule, (m) => (message = m));
    if (value === null) throw new Error(message);
    return value;
  }

  async function applyTransform(what: string, make: () => Transform): Promise<void> {
    await studio.run(async () => {
      const status = await api.transform(make());
      store.update(['status'], (s) => {
        s.status = status;
        s.message = what;
      });
      await studio.reloadAll(true); // the views follow the model (the grid shows where it went)
    });
  }

  $('move-apply').addEventListener('click', () =>
    void applyTransform('moved the model', () => ({
      translate: [numberOf('move-x'), numberOf('move-y'), numberOf('move-z')],
    })),
  );
  $('rotate-apply').addEventListener('click', () =>
    void applyTransform('rotated the model', () => {
      const axis: Vec3 = [0, 0, 0];
      axis[['x', 'y', 'z'].indexOf($<HTMLSelectElement>('rotate-axis').value)] = 1;
      return { rotate: { axis, degrees: numberOf('rotate-degrees') }, center: modelCenter() };
    }),
  );
  $('scale-apply').addEventListener('click', () =>
    void applyTransform('scaled the model', () => ({
      scale: numberOf('scale-factor', { min: 0, nonZero: true }),
      center: modelCenter(),
    })),
  );
}
