// The views drawn from the store: the frame view's handles and frames (or a view-only
// model's curves), the surface view's frame overlay, the captions.
import { $ } from './dom';
import type { Studio } from './studio';

export function overlayWanted(studio: Studio): boolean {
  return $<HTMLInputElement>('overlay').checked && !studio.store.state.viewOnly;
}

export function mountSceneSync(studio: Studio): void {
  const { store, frameView, surfaceView } = studio;
  store.subscribe(['model', 'selection'], (state, topics) => {
    if (state.model) {
      frameView.setModel(state.model, state.selectedVertex, state.selectedFrames);
      surfaceView.updateOverlay(state.model, state.selectedFrames);
    } else if (topics.has('model') && state.view) {
      frameView.showCurves(state.view.curves, state.view.spines);
    }
    if (!topics.has('model')) return;
    $('frame-caption').textContent = !state.viewOnly
      ? 'Vertex frames'
      : state.viewOnly === 'bspline-pde'
        ? 'Control nets (view only)'
        : 'Curves and spine (view only)';
    surfaceView.setOverlay(overlayWanted(studio));
  });
  // A moved vertex (a drag): only its handle and line ends change.
  store.subscribe(['vertex'], (state, topics) => {
    const v = state.selectedVertex;
    if (!state.model || v === null || topics.has('model') || topics.has('selection')) return;
    frameView.moveVertex(v, state.model.vertices[v]);
    surfaceView.moveOverlayVertex(v, state.model.vertices[v]);
  });
}
