// Surface analysis in the right view: zebra stripes with their density and direction, mean
// or Gaussian curvature colours with a legend.
import * as THREE from 'three';
import { api } from './api';
import { $, readNumber } from './dom';
import type { CurvatureMode } from './surface-view';
import type { Studio } from './studio';

const AXIS: Record<string, THREE.Vector3> = {
  x: new THREE.Vector3(1, 0, 0),
  y: new THREE.Vector3(0, 1, 0),
  z: new THREE.Vector3(0, 0, 1),
};

/** A value for the legend: 3 significant digits. */
const legendNumber = (x: number) => (x === 0 ? '0' : Math.abs(x) >= 1e-2 && Math.abs(x) < 1e3 ? String(+x.toPrecision(3)) : x.toExponential(1));

export function mountAnalysis(studio: Studio): void {
  const view = studio.surfaceView;
  const zebra = $<HTMLInputElement>('zebra');
  const density = $<HTMLInputElement>('zebra-density');
  const direction = $<HTMLSelectElement>('zebra-direction');
  const curvature = $<HTMLSelectElement>('curvature');
  const densityValue = $<HTMLInputElement>('zebra-density-value');
  /** The stripes: the slider's, or exactly what was typed in the box beside it. */
  let stripes = Number(density.value);
  const applyZebra = () => view.setZebraOptions(stripes, AXIS[direction.value]);
  zebra.addEventListener('change', () => {
    $('zebra-options').hidden = !zebra.checked;
    view.setZebra(zebra.checked);
    if (zebra.checked && curvature.value !== 'off') {
      curvature.value = 'off'; // one colouring at a time
      view.setCurvature('off');
    }
  });
  density.addEventListener('input', () => {
    stripes = Number(density.value);
    densityValue.value = density.value;
    applyZebra();
  });
  densityValue.addEventListener('change', () => {
    const min = Number(density.min), max = Number(density.max);
    const typed = readNumber(densityValue, { label: 'zebra density', min, max }, (m) => studio.showError(m));
    if (typed === null) return; // refused in place: the stripes stay
    stripes = typed;
    density.value = String(typed);
    applyZebra();
  });
  direction.addEventListener('change', applyZebra);
  applyZebra();

  view.onCurvature = (mode: CurvatureMode, range: number) => {
    $('curvature-legend').hidden = mode === 'off';
    if (mode === 'off') return;
    // Gaussian curvature is 1/length²: its legend says so.
    $('legend-title').textContent = mode === 'mean' ? 'mean curvature H (1/length)' : 'Gaussian curvature K (1/length²)';
    $('legend-min').textContent = `≤ ${legendNumber(-range)}`;
    $('legend-max').textContent = `≥ ${legendNumber(range)}`;
  };
  // The analytic curvature of a vertex-frame model's surface at the chosen resolution,
  // fetched with each new surface while curvature is shown (a preview shows the estimate).
  let asked = 0;
  const fetchCurvature = async () => {
    const mesh = studio.store.state.mesh;
    if (curvature.value === 'off' || !mesh || !studio.store.state.model || studio.previewing()) return;
    const ticket = ++asked;
    try {
      const { revision, values } = await api.curvature({ resolution: mesh.resolution, ...studio.solver });
      // Still the newest request, and of the surface shown: else a later one follows.
      if (ticket === asked && revision === mesh.revision) view.setAnalyticCurvature(mesh, revision, values);
    } catch (e) {
      studio.showError(e);
    }
  };
  studio.store.subscribe(['mesh'], () => void fetchCurvature());
  curvature.addEventListener('change', () => void fetchCurvature());
  curvature.addEventListener('change', () => {
    if (curvature.value !== 'off' && zebra.checked) {
      zebra.checked = false;
      $('zebra-options').hidden = true;
      view.setZebra(false);
    }
    view.setCurvature(curvature.value as CurvatureMode);
  });
}
