// The gizmo (G; Shift+G or the panel's *gizmo* picks its handles): three arrows (and three
// planes) on the centre of the vertex selection in the frame view (of a spectral, cross-section
// or B-spline PDE model: on the chosen curve's centre, curve-editor.ts); dragging one moves the
// selection (the curve) along that axis (or in that plane); or three rings that turn it about
// each axis, or three boxes that scale it along each axis, on the pivot (the panel's pivot:
// each vertex turns and scales about its own, selection-transform.ts pivotsOf; a curve about
// its one, and a picked control point of a net alone, curve-editor.ts). The axes are
// the panel's orientation (global, local, normal: orientation.ts). One undo step per drag, as a
// dragged handle. three.js's TransformControls draws and solves it; its pointer events are fed
// from here, ahead of the handles' drag tool and the orbit controls (a press on the gizmo
// reaches neither).
import * as THREE from 'three';
import { TransformControls } from 'three/examples/jsm/controls/TransformControls.js';
import type { Vec3 } from './api';
import { placeVertices, studioBasis } from './drag';
import { $ } from './dom';
import { mirrorPartners, symmetricMove, symmetryPlane } from './symmetry';
import type { MirrorPlane } from './symmetry';
import { boxCentre, pivotsOf, selectionPieces, singlePivot } from './selection-transform';
import type { Pivot, PivotPlaces } from './selection-transform';
import { GLOBAL_BASIS, isGlobal, scaledAlong, turnedBy } from './orientation';
import type { Basis } from './orientation';
import type { Studio } from './studio';

/** The gizmo's size (TransformControls' unit: about 1/4 of the view's height per 1). */
const GIZMO_SIZE = 0.9;

/** What the gizmo moves: where its arrows sit (`centre`; null: hidden), where its rings and
 * boxes sit (`pivot`), and a drag's steps, each the whole change since the drag's start: `move`
 * by the offset `d`, `turn` by the unit quaternion `q` (x, y, z, w) about the pivot, `scale` by
 * the factors `f` along the axes `basis` about the pivot. `begin` returns false (and says
 * why) when the subject cannot take the handles' kind of change. */
export interface GizmoSubject {
  centre(): Vec3 | null;
  pivot(): Vec3 | null;
  begin(kind: GizmoMode): boolean;
  move(d: Vec3): void;
  turn(q: readonly number[]): void;
  scale(f: Vec3, basis: Basis): void;
  end(): Promise<void>;
}

/** The subject of models without vertices (set by curve-editor.ts), and `changed`: call it
 * when that subject's centre moved or another curve was chosen (set by the gizmo). */
export const gizmoSubjects: { shape?: GizmoSubject; changed?: () => void } = {};

/** What the gizmo's handles do: arrows and planes that move, rings that rotate (about each
 * axis, and the outer ring about the view's direction), boxes that scale along each axis. */
export type GizmoMode = 'translate' | 'rotate' | 'scale';
export const GIZMO_MODES: GizmoMode[] = ['translate', 'rotate', 'scale'];

export interface Gizmo {
  toggle(): void;
  /** Shows the gizmo with its next kind of handles: move, rotate, scale (Shift+G). */
  cycle(): void;
  /** A client point on the handle of `axis` (tests): on the arrow (move) or the box's stem
   * (scale); on the ring (rotate) at `angle` radians from the next axis (x: from y, y: from z,
   * z: from x) toward the one after. Null while the gizmo is hidden. */
  handleScreen(axis: 'x' | 'y' | 'z', angle?: number): { x: number; y: number } | null;
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

/** The panel's pivot for scale and rotate. */
export const pivotChoice = () => ($<HTMLSelectElement>('selection-pivot').value || 'centre') as Pivot;

/** The places a pivot may name: the active vertex (`active`: the one picked last; for curves
 * the handle picked, curve-editor.ts) and the 3D cursor. */
export function pivotPlaces(studio: Studio, active?: Vec3 | null): PivotPlaces {
  const { model, selectedVertex, cursor } = studio.store.state;
  return { active: active !== undefined ? active : model && selectedVertex !== null ? model.vertices[selectedVertex] : null, cursor };
}

/** Each of the vertices' pivot (at `points`), as the panel's *pivot* says (selection-transform.ts
 * pivotsOf: the pieces are those of the vertices, the active vertex the store's). */
export function selectionPivots(studio: Studio, vertices: readonly number[], points: readonly Vec3[]): Vec3[] {
  const model = studio.store.state.model!;
  return pivotsOf(points, pivotChoice(), selectionPieces(vertices, model.frames), pivotPlaces(studio));
}

/** The centre of what is selected: the selected vertices' box (or the selected frames'), or
 * the chosen curve's centre; null when nothing is (the cursor's *to selection*). */
export function selectionCentre(studio: Studio): Vec3 | null {
  const model = studio.store.state.model;
  if (!model) return gizmoSubjects.shape?.centre() ?? null;
  const vertices = selectionVertices(studio);
  return vertices.length ? boxCentre(vertices.map((v) => model.vertices[v])) : null;
}

export function mountGizmo(studio: Studio): Gizmo {
  const { store, frameView, pump } = studio;
  const proxy = new THREE.Object3D();
  frameView.scene.add(proxy);
  const controls = new TransformControls(frameView.camera);
  controls.size = GIZMO_SIZE;
  controls.attach(proxy);
  // Nothing to grab at the centre (a free move, the trackball, a uniform scale): that is a
  // dragged handle's place, and the centre may sit on one.
  const pickers = (controls as unknown as { _gizmo: { picker: Record<GizmoMode, THREE.Object3D> } })._gizmo.picker;
  for (const [mode, name] of [
    ['translate', 'XYZ'],
    ['rotate', 'XYZE'],
    ['scale', 'XYZ'],
  ] as const)
    for (const o of [...pickers[mode].children]) if (o.name === name) pickers[mode].remove(o);
  const helper = controls.getHelper();
  frameView.scene.add(helper);
  let on = false;
  const toggleBox = document.querySelector<HTMLInputElement>('[data-testid="gizmo"]');
  const modeBox = document.querySelector<HTMLSelectElement>('[data-testid="gizmo-mode"]');
  const mode = (): GizmoMode => (modeBox?.value as GizmoMode | undefined) ?? 'translate';
  /** The gizmo's axes (the panel's orientation for the selection), taken when the selection,
   * the model or the choice changes (never during a drag's steps). */
  let basis: Basis = GLOBAL_BASIS;

  /** A drag of the vertex selection: the vertices it moves, where they started, each one's
   * pivot, and with symmetry on the plane and the mirror partners found at the start. */
  let drag: {
    moved: number[];
    from: Vec3[];
    pivots: Vec3[];
    mirror: { plane: MirrorPlane; found: ReturnType<typeof mirrorPartners> } | null;
  } | null = null;

  /** Puts the dragged vertices at `to` (their partners mirrored): the page and the server. */
  const placeDragged = (to: Vec3[]) => {
    if (!drag || !store.state.model) return;
    const { moved, mirror } = drag;
    const { vertices, positions } = mirror ? symmetricMove(mirror.plane, mirror.found, moved, to) : { vertices: moved, positions: to };
    placeVertices(studio, vertices, (i) => positions[i], [], null);
    pump.push(() => ({ op: 'move-vertices', vertices, positions }));
  };

  /** The vertices turned or scaled by `map` (of a vertex's start and its pivot). */
  const transform = (map: (p: Vec3, pivot: Vec3) => Vec3) => {
    if (drag) placeDragged(drag.from.map((p, i) => map(p, drag!.pivots[i])));
  };
  /** The vertex selection as the gizmo's subject: it moves, turns and scales. */
  const vertexSubject: GizmoSubject = {
    centre: () => selectionCentre(studio),
    // The rings and boxes sit on the pivot where it is one place, else on the centre.
    pivot: () => (selectionCentre(studio) && singlePivot(pivotChoice(), pivotPlaces(studio))) ?? selectionCentre(studio),
    begin: () => {
      const model = store.state.model!;
      const moved = selectionVertices(studio);
      const from = moved.map((v) => [...model.vertices[v]] as Vec3);
      const pivots = selectionPivots(studio, moved, from);
      const plane = symmetryPlane($<HTMLSelectElement>('symmetry').value, model.vertices);
      drag = { moved, from, pivots, mirror: plane && { plane, found: mirrorPartners(model.vertices, moved, from, plane) } };
      studio.beginGesture('gizmo');
      return true;
    },
    move: (d) => transform((p) => [p[0] + d[0], p[1] + d[1], p[2] + d[2]]),
    turn: (q) => transform((p, pivot) => turnedBy(p, pivot, q)),
    scale: (f, axes) => transform((p, pivot) => scaledAlong(p, pivot, axes, f)),
    end: async () => {
      drag = null;
      await studio.endGesture();
      store.update(['model'], () => {});
    },
  };
  /** The vertex selection, or the chosen curve of the other model types (curve-editor.ts). */
  const subject = (): GizmoSubject | null => (store.state.model ? vertexSubject : store.state.handles ? (gizmoSubjects.shape ?? null) : null);
  /** Where the drag in progress started (null: none), and the proxy's turn then. */
  let dragStart: THREE.Vector3 | null = null;
  let turnStart = new THREE.Quaternion();

  /** Takes the axes of the panel's orientation for the selection (vertex models only). */
  const orient = () => {
    basis = store.state.model && on ? studioBasis(studio, selectionVertices(studio)) : GLOBAL_BASIS;
    controls.setSpace(isGlobal(basis) ? 'world' : 'local');
    // The handles along the axes, unturned and unscaled (after a drag of the rings or boxes).
    proxy.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(...(basis.map((a) => new THREE.Vector3(...a)) as [THREE.Vector3, THREE.Vector3, THREE.Vector3])));
    proxy.scale.set(1, 1, 1);
  };
  const place = (_state?: unknown, topics?: ReadonlySet<string>) => {
    if (dragStart) return; // the drag moves the proxy itself
    if (!topics || topics.has('model') || topics.has('selection')) orient();
    // The arrows on the centre, the rings and boxes on the pivot.
    const centre = (mode() === 'translate' ? subject()?.centre() : subject()?.pivot()) ?? null;
    const wasVisible = helper.visible;
    helper.visible = on && centre !== null;
    controls.enabled = helper.visible;
    if (centre) proxy.position.set(...centre);
    // Only a shown gizmo (or one shown or hidden now) needs the frame view drawn whole: a
    // hidden one must not turn a vertex drag's region redraw (frame-view.ts) into whole draws.
    if (helper.visible || wasVisible) frameView.invalidate();
  };
  store.subscribe(['model', 'selection', 'vertex'], place);
  gizmoSubjects.changed = () => place();
  const setMode = (m: GizmoMode) => {
    if (modeBox) modeBox.value = m;
    controls.setMode(m);
    place();
  };
  const toggle = () => {
    on = !on;
    if (toggleBox) toggleBox.checked = on;
    place();
  };
  toggleBox?.addEventListener('change', () => {
    if (toggleBox.checked !== on) toggle();
  });
  modeBox?.addEventListener('change', () => setMode(mode()));
  for (const id of ['orientation', 'selection-pivot']) document.querySelector(`[data-testid="${id}"]`)?.addEventListener('change', () => place());
  store.subscribe(['cursor'], () => place()); // on the cursor, when it is the pivot

  controls.addEventListener('change', () => frameView.invalidate());
  // The subject of a drag is kept from its press to its release.
  let dragging: GizmoSubject | null = null;
  controls.addEventListener('mouseDown', () => {
    dragging = subject();
    if (!dragging) return;
    dragStart = proxy.position.clone();
    turnStart = proxy.quaternion.clone();
    if (!dragging.begin(mode())) dragging = null;
  });
  controls.addEventListener('objectChange', () => {
    if (!dragging || !dragStart) return;
    const kind = mode();
    if (kind === 'translate') {
      const d = proxy.position.clone().sub(dragStart);
      dragging.move([d.x, d.y, d.z]);
    } else if (kind === 'rotate') {
      // The turn since the press, in world axes, about the pivot (each vertex's own).
      const q = proxy.quaternion.clone().multiply(turnStart.clone().invert());
      dragging.turn([q.x, q.y, q.z, q.w]);
    } else {
      // Scale along the gizmo's axes (TransformControls scales in the proxy's own).
      dragging.scale([proxy.scale.x, proxy.scale.y, proxy.scale.z], basis);
    }
  });
  controls.addEventListener('mouseUp', () => {
    const was = dragging;
    dragging = null;
    dragStart = null;
    if (was) void was.end().then(() => place());
    else place(); // a drag the subject refused: the handles back as they were
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
    cycle() {
      const next = on ? GIZMO_MODES[(GIZMO_MODES.indexOf(mode()) + 1) % GIZMO_MODES.length] : mode();
      if (!on) toggle();
      setMode(next);
      studio.say(`gizmo: ${next === 'translate' ? 'move' : next}${next === 'translate' ? '' : `, about ${$<HTMLSelectElement>('selection-pivot').selectedOptions[0]?.textContent ?? 'the pivot'}`}`);
    },
    handleScreen(axis, angle = 0) {
      if (!helper.visible) return null;
      // TransformControls scales its handles so: distance × min(1.9 tan(fov/2) / zoom, 7) × size / 4.
      const camera = frameView.camera;
      const unit = (proxy.position.distanceTo(camera.position) * Math.min((1.9 * Math.tan((Math.PI * camera.fov) / 360)) / camera.zoom, 7) * controls.size) / 4;
      const k = 'xyz'.indexOf(axis);
      const along = (i: number) => new THREE.Vector3(...basis[i % 3]);
      // An arrow's (a box's) picker runs from 0 to 0.6 along its axis: press at 0.45; a ring
      // has radius 0.5.
      const at =
        mode() === 'rotate'
          ? along(k + 1).multiplyScalar(Math.cos(angle)).addScaledVector(along(k + 2), Math.sin(angle)).multiplyScalar(0.5 * unit)
          : along(k).multiplyScalar(0.45 * unit);
      const s = frameView.toClient(proxy.position.clone().add(at));
      return { x: s.x, y: s.y };
    },
  };
}
