// The views drawn from the store: the frame view's handles and frames (or a view-only
// model's curves), the surface view's frame overlay, the captions.
import { api } from './api';
import { $ } from './dom';
import type { Studio } from './studio';

/** Models up to this many frames get their boundary curves with every surface during a
 * drag that is not previewed; larger ones, and previewed ones, when the gesture ends (a
 * 1,000-frame model's curves are 0.8 MB). */
export const BOUNDARIES_LIVE_FRAMES = 200;
/** Samples per side of a boundary curve at most. */
const BOUNDARY_MAX_SAMPLES = 33;

export function overlayWanted(studio: Studio): boolean {
  return $<HTMLInputElement>('overlay').checked && studio.store.state.hasEditableParts;
}

export function mountSceneSync(studio: Studio): void {
  const { store, frameView, surfaceView } = studio;
  store.subscribe(['model', 'selection'], (state, topics) => {
    if (state.model) {
      frameView.setModel(state.model, state.selectedVertex, state.selectedFrames, state.selectedVertices);
      surfaceView.selectOverlay(state.selectedFrames);
    } else if (topics.has('model') && state.view) {
      frameView.showCurves(state.view.curves, state.view.spines);
      surfaceView.setBoundaries(null, state.selectedFrames);
    }
    if (!topics.has('model')) return;
    $('frame-caption').textContent = state.hasEditableParts ? 'Vertex frames' : (state.settings?.overlay ?? '');
    surfaceView.setOverlay(overlayWanted(studio));
  });
  // A moved vertex (a drag): only its handle and line ends change.
  store.subscribe(['vertex'], (state, topics) => {
    const v = state.selectedVertex;
    if (!state.model || v === null || topics.has('model') || topics.has('selection')) return;
    frameView.moveVertex(v, state.model.vertices[v]);
  });
  // The surface's frame overlay: the patches' true boundary curves, fetched with each new
  // surface (of a large model only when a gesture ends).
  let asked = 0;
  let shown = 0;
  const fetchBoundaries = async () => {
    const s = store.state;
    if (!s.model || !overlayWanted(studio)) return;
    // During a preview the curves are hidden (SurfaceView.setPreview): fetched at its end.
    if (studio.gesture && (studio.previewing() || s.model.frames.length > BOUNDARIES_LIVE_FRAMES)) return;
    const ticket = ++asked;
    try {
      // As many samples a side as the surface's (so the curves pass through its vertices).
      const curves = await api.boundaries(Math.min(BOUNDARY_MAX_SAMPLES, studio.fullResolution()), studio.solver);
      if (ticket < shown || !store.state.model) return; // a later answer is shown already
      shown = ticket;
      surfaceView.setBoundaries(curves, store.state.selectedFrames);
    } catch (e) {
      studio.showError(e);
    }
  };
  store.subscribe(['mesh'], () => void fetchBoundaries());
  $('overlay').addEventListener('change', () => void fetchBoundaries());
}
