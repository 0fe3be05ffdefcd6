// The move gizmo (G): three arrows (and three planes) on the centre of the vertex selection
// in the frame view (of a spectral, cross-section or B-spline PDE model: on the chosen
// curve's centre, curve-editor.ts); dragging one moves the selection (the curve) along that
// axis (or in that plane), one undo step per drag, as a dragged handle does. three.js's TransformControls draws and
// solves it; its pointer events are fed from here, ahead of the handles' drag tool and the
// orbit controls (a press on the gizmo reaches neither).
import * as THREE from 'three';
import { TransformControls } from 'three/examples/jsm/controls/TransformControls.js';
import type { Vec3 } from './api';
import { placeVertices } from './drag';
import { $ } from './dom';
import { mirrorPartners, symmetricMove, symmetryPlane } from './symmetry';
import type { MirrorPlane } from './symmetry';
import { boxCentre } from './selection-transform';
import type { Studio } from './studio';

/** The gizmo's size (TransformControls' unit: about 1/4 of the view's height per 1). */
const GIZMO_SIZE = 0.9;

/** What the gizmo moves: where it sits (null: hidden) and a drag's steps (`d`: the offset
 * from the drag's start). */
export interface GizmoSubject {
  centre(): Vec3 | null;
  begin(): void;
  move(d: Vec3): void;
  end(): Promise<void>;
}

/** The subject of models without vertices (set by curve-editor.ts), and `changed`: call it
 * when that subject's centre moved or another curve was chosen (set by the gizmo). */
export const gizmoSubjects: { shape?: GizmoSubject; changed?: () => void } = {};

export interface Gizmo {
  toggle(): void;
  /** A client point on the arrow of `axis` (tests). */
  arrowScreen(axis: 'x' | 'y' | 'z'): { x: number; y: number } | null;
}

/** The vertices a selection tool acts on: the selected vertices, else the selected frames'. */
export function selectionVertices(studio: Studio): number[] {
  const s = studio.store.state;
  if (s.selectedVertices.length) return [...s.selectedVertices];
  if (s.selectedVertex !== null) return [s.selectedVertex];
  const all = new Set<number>();
  for (const f of s.selectedFrames) for (const v of s.model?.frames[f]?.vertices ?? []) all.add(v);
  return [...all].sort((a, b) => a - b);
}

export function mountGizmo(studio: Studio): Gizmo {
  const { store, frameView, pump } = studio;
  const proxy = new THREE.Object3D();
  frameView.scene.add(proxy);
  const controls = new TransformControls(frameView.camera);
  controls.size = GIZMO_SIZE;
  controls.attach(proxy);
  // No free (screen-plane) move at the centre: that is a dragged handle's, and the centre
  // may sit on one.
  const picker = (controls as unknown as { _gizmo: { picker: { translate: THREE.Object3D } } })._gizmo.picker.translate;
  for (const o of [...picker.children]) if (o.name === 'XYZ') picker.remove(o);
  const helper = controls.getHelper();
  frameView.scene.add(helper);
  let on = false;
  const toggleBox = document.querySelector<HTMLInputElement>('[data-testid="gizmo"]');

  /** A drag of the vertex selection: the vertices it moves, where they started, and with
   * symmetry on the plane and the mirror partners found at the start. */
  let drag: { moved: number[]; from: Vec3[]; mirror: { plane: MirrorPlane; found: ReturnType<typeof mirrorPartners> } | null } | null = null;

  /** The vertex selection as the gizmo's subject. */
  const vertexSubject: GizmoSubject = {
    centre: () => {
      const model = store.state.model;
      const vertices = model ? selectionVertices(studio) : [];
      return vertices.length ? boxCentre(vertices.map((v) => model!.vertices[v])) : null;
    },
    begin: () => {
      const model = store.state.model!;
      const moved = selectionVertices(studio);
      const from = moved.map((v) => [...model.vertices[v]] as Vec3);
      const plane = symmetryPlane($<HTMLSelectElement>('symmetry').value, model.vertices);
      drag = { moved, from, mirror: plane && { plane, found: mirrorPartners(model.vertices, moved, from, plane) } };
      studio.beginGesture('gizmo');
    },
    move: (d) => {
      if (!drag || !store.state.model) return;
      const { moved, from, mirror } = drag;
      const to = from.map((p) => [p[0] + d[0], p[1] + d[1], p[2] + d[2]] as Vec3);
      const { vertices, positions } = mirror ? symmetricMove(mirror.plane, mirror.found, moved, to) : { vertices: moved, positions: to };
      placeVertices(studio, vertices, (i) => positions[i], [], null);
      pump.push(() => ({ op: 'move-vertices', vertices, positions }));
    },
    end: async () => {
      drag = null;
      await studio.endGesture();
      store.update(['model'], () => {});
    },
  };
  const subject = (): GizmoSubject | null => (store.state.model ? vertexSubject : store.state.shape ? (gizmoSubjects.shape ?? null) : null);
  /** Where the drag in progress started (null: none). */
  let dragStart: THREE.Vector3 | null = null;

  const place = () => {
    const centre = subject()?.centre() ?? null;
    const wasVisible = helper.visible;
    helper.visible = on && centre !== null;
    controls.enabled = helper.visible;
    if (centre && !dragStart) proxy.position.set(...centre);
    // Only a shown gizmo (or one shown or hidden now) needs the frame view drawn whole: a
    // hidden one must not turn a vertex drag's region redraw (frame-view.ts) into whole draws.
    if (helper.visible || wasVisible) frameView.invalidate();
  };
  store.subscribe(['model', 'selection', 'vertex'], place);
  gizmoSubjects.changed = place;
  const toggle = () => {
    on = !on;
    if (toggleBox) toggleBox.checked = on;
    place();
  };
  toggleBox?.addEventListener('change', () => {
    if (toggleBox.checked !== on) toggle();
  });

  controls.addEventListener('change', () => frameView.invalidate());
  // The subject of a drag is kept from its press to its release.
  let dragging: GizmoSubject | null = null;
  controls.addEventListener('mouseDown', () => {
    dragging = subject();
    if (!dragging) return;
    dragStart = proxy.position.clone();
    dragging.begin();
  });
  controls.addEventListener('objectChange', () => {
    if (!dragging || !dragStart) return;
    const d = proxy.position.clone().sub(dragStart);
    dragging.move([d.x, d.y, d.z]);
  });
  controls.addEventListener('mouseUp', () => {
    const was = dragging;
    dragging = null;
    dragStart = null;
    if (was) void was.end().then(place);
  });

  // The pointer, fed to the controls in the capture phase of the view's container (before
  // the canvas' own listeners: the drag tool and the orbit controls).
  const container = frameView.container;
  const pointer = (ev: PointerEvent) => {
    const rect = frameView.renderer.domElement.getBoundingClientRect();
    const p = { x: ((ev.clientX - rect.left) / rect.width) * 2 - 1, y: -((ev.clientY - rect.top) / rect.height) * 2 + 1, button: ev.button };
    // The controls take the pointer as their own listeners make it (typed as the event).
    return p as unknown as PointerEvent;
  };
  let capturing: number | null = null;
  container.addEventListener(
    'pointerdown',
    (ev) => {
      if (!controls.enabled || ev.button !== 0) return;
      controls.pointerHover(pointer(ev));
      if (controls.axis === null) return;
      ev.stopPropagation();
      ev.preventDefault();
      capturing = ev.pointerId;
      container.setPointerCapture(ev.pointerId);
      controls.pointerDown(pointer(ev));
    },
    true,
  );
  container.addEventListener(
    'pointermove',
    (ev) => {
      if (!controls.enabled) return;
      if (capturing === ev.pointerId) {
        ev.stopPropagation();
        controls.pointerMove(pointer(ev));
      } else if (ev.buttons === 0) {
        const before = controls.axis;
        controls.pointerHover(pointer(ev));
        if (controls.axis !== before) frameView.invalidate();
      }
    },
    true,
  );
  const release = (ev: PointerEvent) => {
    if (capturing !== ev.pointerId) return;
    ev.stopPropagation();
    capturing = null;
    container.releasePointerCapture(ev.pointerId);
    controls.pointerUp(pointer(ev));
  };
  container.addEventListener('pointerup', release, true);
  container.addEventListener('pointercancel', release, true);

  return {
    toggle,
    arrowScreen(axis) {
      if (!helper.visible) return null;
      // TransformControls scales its handles so: distance × min(1.9 tan(fov/2) / zoom, 7) × size / 4.
      const camera = frameView.camera;
      const factor =
        proxy.position.distanceTo(camera.position) * Math.min((1.9 * Math.tan((Math.PI * camera.fov) / 360)) / camera.zoom, 7);
      const along = new THREE.Vector3(axis === 'x' ? 1 : 0, axis === 'y' ? 1 : 0, axis === 'z' ? 1 : 0);
      // The arrow's picker runs from 0 to 0.6 along its axis: press at 0.45.
      const s = frameView.toClient(proxy.position.clone().addScaledVector(along, (0.45 * factor * controls.size) / 4));
      return { x: s.x, y: s.y };
    },
  };
}
