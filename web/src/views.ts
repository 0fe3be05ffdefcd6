// View presets, fit all / fit selection, and linked cameras (orbiting one view moves the
// other). Presets and fits apply to both views: they show the same model in the same space.
import * as THREE from 'three';
import { $, makeButton } from './dom';
import { modelBox, pointsBox } from './viewport';
import type { ViewName } from './viewport';
import type { State } from './store';
import type { Studio } from './studio';

/** The whole model's box: its vertices, its view-only curves, or its surface. */
export function allBox(state: Readonly<State>): THREE.Box3 {
  if (state.model) return modelBox(state.model);
  if (state.view) return pointsBox([...state.view.curves, ...state.view.spines]);
  return new THREE.Box3();
}

/** The selection's box: the selected frames' vertices, or the frames around the selected
 * vertex; empty when nothing is selected. */
export function selectionBox(state: Readonly<State>): THREE.Box3 {
  const box = new THREE.Box3();
  const model = state.model;
  if (!model) return box;
  const add = (f: number) => model.frames[f].vertices.forEach((v) => box.expandByPoint(new THREE.Vector3(...model.vertices[v])));
  for (const f of state.selectedFrames) add(f);
  if (box.isEmpty() && state.selectedVertex !== null) {
    model.frames.forEach((frame, f) => frame.vertices.includes(state.selectedVertex!) && add(f));
    box.expandByPoint(new THREE.Vector3(...model.vertices[state.selectedVertex]));
  }
  return box;
}

/** The standard views: each a button in the header (its label) and a key (keys.ts). */
export const VIEWS: readonly { name: ViewName; label: string; key: string; what: string }[] = [
  { name: 'front', label: 'Front', key: '1', what: 'Front view (looking along +y)' },
  { name: 'back', label: 'Back', key: '2', what: 'Back view' },
  { name: 'right', label: 'Right', key: '3', what: 'Right view (looking along -x)' },
  { name: 'left', label: 'Left', key: '4', what: 'Left view' },
  { name: 'top', label: 'Top', key: '5', what: 'Top view (looking down z)' },
  { name: 'bottom', label: 'Bottom', key: '6', what: 'Bottom view' },
  { name: 'iso', label: '3/4', key: '0', what: 'Three-quarter view' },
];

export interface ViewActions {
  view(name: ViewName): void;
  fitAll(): void;
  fitSelection(): void;
  toggleLink(): void;
}

export function mountViews(studio: Studio): ViewActions {
  const { store, frameView, surfaceView } = studio;
  const both = [frameView, surfaceView];
  const link = $<HTMLInputElement>('link-cameras');

  // Linked: a camera change in one view is copied to the other (never back: `following`).
  let following = false;
  for (const [from, to] of [[frameView, surfaceView], [surfaceView, frameView]] as const)
    from.controls.addEventListener('change', () => {
      if (!link.checked || following) return;
      following = true;
      to.follow(from);
      following = false;
    });
  link.addEventListener('change', () => link.checked && surfaceView.follow(frameView));

  const actions: ViewActions = {
    view(name) {
      const box = allBox(store.state);
      for (const v of both) v.setView(name, box);
      store.update(['status'], (s) => (s.message = `${name} view`));
    },
    fitAll() {
      const box = allBox(store.state);
      for (const v of both) v.fit(box);
    },
    fitSelection() {
      const box = selectionBox(store.state);
      if (box.isEmpty()) return actions.fitAll();
      for (const v of both) v.fit(box);
    },
    toggleLink() {
      link.checked = !link.checked;
      link.dispatchEvent(new Event('change'));
    },
  };
  $('fit-all').before(...VIEWS.map((v) => makeButton(`view-${v.name}`, v.label, `${v.what} (${v.key})`, () => actions.view(v.name))));
  $('fit-all').addEventListener('click', () => actions.fitAll());
  $('fit-selection').addEventListener('click', () => actions.fitSelection());
  return actions;
}
