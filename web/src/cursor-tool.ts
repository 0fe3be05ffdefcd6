// The 3D cursor, as Blender's: a marker in both views (a red and white ring with cross hairs,
// drawn over everything), placed by Shift+right-click (on the surface under the pointer, else
// in the plane through the cursor that faces the camera: cursor.ts), typed in the panel's
// cursor boxes (numbers or expressions), or put on the selection's centre or the origin. With
// the panel's pivot *the 3D cursor*, rotate and scale (the gizmo's rings and boxes, Shift+R,
// Shift+S) turn about it. It is the view's, not the model's: never in the model file; the
// browser keeps it for each model file (localStorage), so a reload or a reopen finds it again.
import * as THREE from 'three';
import type { Vec3 } from './api';
import { $, readNumber } from './dom';
import { CURSOR_STORAGE_KEY, cursorFromRay, storedCursor, withStoredCursor } from './cursor';
import { selectionCentre } from './gizmo';
import { onSurface } from './snap';
import type { Studio } from './studio';

/** The marker's diameter in CSS pixels (a selected handle is 14). */
const CURSOR_PIXELS = 28;

const CURSOR_VERTEX = /* glsl */ `
uniform float size;
void main() {
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
  gl_PointSize = size;
}`;

// A ring of red and white eighths, and dark cross hairs from it outward (Blender's cursor).
const CURSOR_FRAGMENT = /* glsl */ `
void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r = length(d);
  if (r > 0.55 && r < 0.8) {
    float eighth = floor(atan(d.y, d.x) / 0.7853981634 + 8.0);
    gl_FragColor = mod(eighth, 2.0) < 1.0 ? vec4(0.86, 0.12, 0.12, 1.0) : vec4(1.0);
    return;
  }
  if ((abs(d.x) < 0.07 || abs(d.y) < 0.07) && r > 0.25 && r <= 1.0) {
    gl_FragColor = vec4(0.1, 0.1, 0.12, 1.0);
    return;
  }
  discard;
}`;

const AXES = ['x', 'y', 'z'] as const;

export function mountCursor(studio: Studio): void {
  const { store, frameView, surfaceView } = studio;

  // One marker per view (an object has one scene), sharing the point and the material.
  const geometry = new THREE.BufferGeometry();
  const position = new THREE.BufferAttribute(new Float32Array(3), 3);
  geometry.setAttribute('position', position);
  const material = new THREE.ShaderMaterial({
    uniforms: { size: { value: CURSOR_PIXELS * frameView.renderer.getPixelRatio() } },
    vertexShader: CURSOR_VERTEX,
    fragmentShader: CURSOR_FRAGMENT,
    depthTest: false,
  });
  for (const view of [frameView, surfaceView]) {
    const marker = new THREE.Points(geometry, material);
    marker.frustumCulled = false;
    marker.renderOrder = 10; // over the surface, the frames and the handles
    view.scene.add(marker);
  }

  // Kept per model file by the browser (storage may be off: then for this page only).
  const stored = () => {
    try {
      return localStorage.getItem(CURSOR_STORAGE_KEY);
    } catch {
      return null;
    }
  };
  const keep = (path: string, p: Vec3) => {
    try {
      localStorage.setItem(CURSOR_STORAGE_KEY, withStoredCursor(stored(), path, p));
    } catch {
      // no storage: the cursor lives as long as the page
    }
  };

  const place = (p: Vec3, how: string) => {
    store.update(['cursor'], (s) => (s.cursor = [...p]));
    keep(store.state.path, p);
    studio.say(`3D cursor ${how}: (${p.map((x) => +x.toFixed(4)).join(', ')})`);
  };

  // Another model file: its own cursor (the origin until one is placed).
  let path: string | null = null;
  store.subscribe(['status'], (state) => {
    if (state.path === path) return;
    path = state.path;
    const p = storedCursor(stored(), path) ?? [0, 0, 0];
    store.update(['cursor'], (s) => (s.cursor = p));
  });

  store.subscribe(['cursor'], (state) => {
    position.set(state.cursor);
    position.needsUpdate = true;
    frameView.invalidate();
    surfaceView.invalidate();
    AXES.forEach((a, i) => {
      const box = $<HTMLInputElement>(`cursor-${a}`);
      if (document.activeElement === box) return;
      box.value = String(+state.cursor[i].toFixed(6));
      box.classList.remove('invalid');
      box.setCustomValidity('');
    });
  });

  AXES.forEach((a, i) => {
    const box = $<HTMLInputElement>(`cursor-${a}`);
    box.addEventListener('change', () => {
      const value = readNumber(box, { label: `cursor ${a}` }, (m) => studio.showError(m));
      if (value === null) return; // refused in place: the cursor stays
      const p = [...store.state.cursor] as Vec3;
      p[i] = value;
      place(p, 'typed');
      box.value = String(+value.toFixed(6)); // the number, not the expression typed
    });
  });
  $('cursor-to-selection').addEventListener('click', () => {
    const centre = selectionCentre(studio);
    if (centre) place(centre, 'on the selection');
    else studio.showError('3D cursor to selection: select vertices, frames or a curve first');
  });
  $('cursor-to-origin').addEventListener('click', () => place([0, 0, 0], 'at the origin'));

  // Shift+right-click in either view, taken in the capture phase of its container (before the
  // orbit controls' pan). The surface is the one the surface view shows (in the frame view
  // too: the same space).
  for (const view of [frameView, surfaceView]) {
    view.container.addEventListener(
      'pointerdown',
      (ev) => {
        if (ev.button !== 2 || !ev.shiftKey) return;
        ev.stopPropagation();
        ev.preventDefault();
        surfaceView.mesh.geometry.computeBoundingSphere(); // deltas move vertices, not the bounds
        const hit = store.state.mesh ? onSurface(surfaceView.mesh, view, ev.clientX, ev.clientY) : null;
        const facing = view.camera.getWorldDirection(new THREE.Vector3());
        const p = cursorFromRay(view.ray(ev.clientX, ev.clientY), hit, store.state.cursor, facing);
        place(p, hit ? 'on the surface' : 'in the plane facing the camera');
      },
      true,
    );
    view.container.addEventListener('contextmenu', (ev) => ev.shiftKey && ev.preventDefault(), true);
  }
}
