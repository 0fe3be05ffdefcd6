// Forces placed on the surface: the regions of the selected frame's forces drawn on its patch
// (the selected one with handles, and its effect arrow), the patches of the shared forces over
// the selected frames (seed Fig. 9) outlined (the one over exactly them with an effect arrow on
// each patch); with Draw force on (D), a drag on a patch makes a new force over the
// rectangle it spans in the patch's (u, v); a region's corner handles resize it and its
// centre handle moves it. Each change is one set-forces edit (one undo step); the panel's
// u0 u1 v0 v1 boxes show the same numbers. Points and parameters come from the server's
// solved patches (POST /api/patch-points, /api/patch-uv), so the outlines lie on the surface.
import * as THREE from 'three';
import { api } from './api';
import type { FrameForce, Region, Vec3 } from './api';
import { $ } from './dom';
import { forceDisplacement, moveRegion, regionCorners, regionFromCorners, regionOutline, resizeRegion, sharedDisplacements, sharedForceOf } from './regions';
import type { UV } from './regions';
import type { Studio } from './studio';
import type { SurfacePicker } from './surface-pick';

/** Points per side of an outline. */
const OUTLINE_SAMPLES = 12;
/** A press within this many pixels of a handle takes it. */
const HANDLE_PICK_PIXELS = 10;
const HANDLE_PIXELS = 11;
/** Frames selected beyond this many get no outlines (one request per frame). */
const MAX_OUTLINED_FRAMES = 16;

const REGION_COLOR = new THREE.Color(0x7b2cbf);
const SELECTED_COLOR = new THREE.Color(0xee6c4d);
const SHARED_COLOR = new THREE.Color(0x2a9d3f);
/** The selected force's effect arrow: dark red, its head this fraction of its length. */
const EFFECT_COLOR = 0xb5179e;
const EFFECT_HEAD = 0.25;

/** Handles: the selected region's corners 0..3 (regionCorners' order), then its centre. */
export const CENTRE_HANDLE = 4;

export interface ForcesTool {
  toggleDraw(): void;
  /** The client point of a handle of the selected force (tests). */
  handleScreen(handle: number): { x: number; y: number } | null;
  /** The effect arrow of the selected force (world points: its tail and its tip, the region's
   * middle on the surface), or null while none is shown. */
  effect(): { from: Vec3; to: Vec3 } | null;
  /** The effect arrows of the shared force over the selected frames, one on each of its
   * frames' patches (tail, tip on the patch's middle), or none. */
  sharedEffects(): { frame: number; from: Vec3; to: Vec3 }[];
  /** The outlines drawn: each one's frame and region (tests). */
  drawn(): { frame: number; region: Region }[];
  /** The client point of (u, v) on frame `frame`'s patch (tests). */
  uvScreen(frame: number, uv: UV): Promise<{ x: number; y: number }>;
}

interface Outline {
  frame: number;
  region: Region;
  color: THREE.Color;
}

/** A gesture on the surface: a new region being drawn, or a handle dragged. */
interface Gesture {
  pointer: number;
  frame: number;
  /** The force changed (-1: a new one). */
  force: number;
  handle: number;
  start: Region;
  /** Where the drag started, in the patch's parameters (resolves once the server answers). */
  from: Promise<UV | null>;
  region: Region;
  /** The latest parameter request: answers to older ones are dropped. */
  asked: number;
  /** Where the press was (a press that does not move draws nothing). */
  x: number;
  y: number;
}

/** Presses that move less than this many pixels are clicks. */
const CLICK_PIXELS = 5;

export function mountForcesTool(studio: Studio, picker: SurfacePicker): ForcesTool {
  const { store, surfaceView, pump } = studio;
  const lines = new THREE.LineSegments(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true }),
  );
  lines.renderOrder = 4;
  lines.frustumCulled = false;
  const handles = new THREE.Points(
    new THREE.BufferGeometry(),
    new THREE.PointsMaterial({ color: SELECTED_COLOR, size: HANDLE_PIXELS, sizeAttenuation: false, depthTest: false }),
  );
  handles.renderOrder = 5;
  handles.frustumCulled = false;
  // The selected force's effect: an arrow from where its region's middle would be without it
  // to where it is (forceDisplacement), redrawn as its f0 sliders move.
  const effect = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, EFFECT_COLOR);
  effect.visible = false;
  effect.renderOrder = 5;
  for (const part of [effect.line, effect.cone]) (part.material as THREE.Material).depthTest = false;
  surfaceView.scene.add(lines, handles, effect);
  // The shared force's: one arrow per frame (made as needed, kept hidden when not).
  const sharedArrows: THREE.ArrowHelper[] = [];
  const sharedArrow = (i: number) => {
    while (sharedArrows.length <= i) {
      const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, EFFECT_COLOR);
      a.renderOrder = 5;
      for (const part of [a.line, a.cone]) (part.material as THREE.Material).depthTest = false;
      surfaceView.scene.add(a);
      sharedArrows.push(a);
    }
    return sharedArrows[i];
  };
  let sharedShown: number[] = []; // the frame of each shown shared arrow

  let drawing = false;
  const button = $<HTMLButtonElement>('draw-force');
  const toggleDraw = () => {
    drawing = !drawing;
    button.setAttribute('aria-pressed', String(drawing));
    button.classList.toggle('on', drawing);
    surfaceView.renderer.domElement.style.cursor = drawing ? 'crosshair' : '';
    studio.say(drawing ? 'Draw force: drag a rectangle on a patch' : 'Draw force off');
  };
  button.addEventListener('click', toggleDraw);

  let gesture: Gesture | null = null;
  /** The selected force's handles on screen's world points: corners, then centre. */
  let handlePoints: THREE.Vector3[] = [];
  let handleOf: { frame: number; force: number; region: Region } | null = null;

  /** What to outline now: the selected frame's regions (or the gesture's), shared forces. */
  function outlines(): { list: Outline[]; selected: { frame: number; force: number; region: Region } | null } {
    const s = store.state;
    const model = s.model;
    const list: Outline[] = [];
    let selected: { frame: number; force: number; region: Region } | null = null;
    if (!model) return { list, selected };
    const frames = [...s.selectedFrames].sort((a, b) => a - b).slice(0, MAX_OUTLINED_FRAMES);
    if (frames.length === 1) {
      const f = frames[0];
      const forces = model.frames[f]?.forces ?? [];
      const k = Math.min(s.selectedForce, forces.length - 1);
      forces.forEach((force, i) => {
        const region = gesture && gesture.frame === f && gesture.force === i ? gesture.region : (force.region ?? [0, 1, 0, 1]);
        list.push({ frame: f, region, color: i === k ? SELECTED_COLOR : REGION_COLOR });
        if (i === k) selected = { frame: f, force: i, region };
      });
    }
    if (gesture && gesture.force < 0) list.push({ frame: gesture.frame, region: gesture.region, color: SELECTED_COLOR });
    const picked = new Set(frames);
    for (const shared of model.forces ?? [])
      if (shared.frames.some((f) => picked.has(f)))
        for (const f of shared.frames) list.push({ frame: f, region: [0, 1, 0, 1], color: SHARED_COLOR });
    return { list, selected };
  }

  let ticket = 0;
  let drawn: { frame: number; region: Region }[] = [];
  /** Fetches the outlines' points (one request per frame) and draws them. */
  async function redraw(): Promise<void> {
    const mine = ++ticket;
    const { list, selected } = outlines();
    if (!list.length && !selected && !drawn.length && !handlePoints.length) return; // nothing shown, nothing to show
    const byFrame = new Map<number, UV[]>();
    const uvOf = (f: number) => byFrame.get(f) ?? (byFrame.set(f, []), byFrame.get(f)!);
    const spans = list.map((o) => {
      const uv = uvOf(o.frame);
      const first = uv.length;
      uv.push(...regionOutline(o.region, OUTLINE_SAMPLES));
      return first;
    });
    // The shared force the f0 sliders set (over exactly the selected frames): its patches'
    // middles, where its arrows end.
    const frames = [...store.state.selectedFrames].sort((a, b) => a - b);
    const shared = frames.length > 1 && frames.length <= MAX_OUTLINED_FRAMES ? sharedForceOf(store.state.model, frames) : undefined;
    const middles = (shared?.frames ?? []).map((f) => {
      const uv = uvOf(f);
      uv.push([0.5, 0.5]);
      return uv.length - 1;
    });
    let handleFirst = -1;
    if (selected) {
      const uv = uvOf(selected.frame);
      handleFirst = uv.length;
      const r = selected.region;
      uv.push(...regionCorners(r), [(r[0] + r[1]) / 2, (r[2] + r[3]) / 2]);
    }
    const points = new Map<number, Vec3[]>();
    try {
      await Promise.all([...byFrame].map(async ([f, uv]) => points.set(f, await api.patchPoints(f, uv, studio.solver))));
    } catch (e) {
      if (mine === ticket) studio.showError(e);
      return;
    }
    if (mine !== ticket) return; // a later redraw is on its way
    const n = 4 * OUTLINE_SAMPLES;
    const position = new Float32Array(list.length * n * 6);
    const color = new Float32Array(list.length * n * 6);
    list.forEach((o, i) => {
      const p = points.get(o.frame)!;
      for (let j = 0; j < n; ++j) {
        const k = 6 * (i * n + j);
        position.set(p[spans[i] + j], k);
        position.set(p[spans[i] + ((j + 1) % n)], k + 3);
        for (const at of [k, k + 3]) color.set([o.color.r, o.color.g, o.color.b], at);
      }
    });
    drawn = list.map((o) => ({ frame: o.frame, region: o.region }));
    lines.geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
    lines.geometry.setAttribute('color', new THREE.BufferAttribute(color, 3));
    handlePoints = selected ? points.get(selected.frame)!.slice(handleFirst, handleFirst + 5).map((q) => new THREE.Vector3(...q)) : [];
    handleOf = selected;
    handles.geometry.setAttribute('position', new THREE.Float32BufferAttribute(handlePoints.flatMap((q) => q.toArray()), 3));
    showEffect(selected);
    showSharedEffects(shared ? sharedDisplacements(store.state.model!, shared).map((m, i) => ({ ...m, tip: points.get(m.frame)![middles[i]] })) : []);
    surfaceView.invalidate();
  }
  store.subscribe(['model', 'selection', 'forces', 'mesh'], () => void redraw());

  /** Points `arrow` from `tip` − `d` to `tip`; hidden when `d` is 0 or not a number. */
  function pointArrow(arrow: THREE.ArrowHelper, tip: THREE.Vector3, d: readonly number[]): void {
    const along = new THREE.Vector3(...d);
    const length = along.length();
    arrow.visible = length > 0 && Number.isFinite(length);
    if (!arrow.visible) return;
    arrow.position.copy(tip).sub(along);
    arrow.setDirection(along.normalize());
    arrow.setLength(length, EFFECT_HEAD * length, EFFECT_HEAD * length * 0.6);
  }

  /** The shared force's arrows, each ending at its frame's patch middle on the surface. */
  function showSharedEffects(moves: { frame: number; d: readonly number[]; tip: Vec3 }[]): void {
    sharedArrows.forEach((a) => (a.visible = false));
    sharedShown = [];
    moves.forEach((m, i) => {
      pointArrow(sharedArrow(i), new THREE.Vector3(...m.tip), m.d);
      sharedShown.push(m.frame);
    });
  }

  /** The effect arrow of the selected force, ending at its region's middle on the surface. */
  function showEffect(selected: { frame: number; force: number } | null): void {
    const frame = selected && store.state.model?.frames[selected.frame];
    const force = frame?.forces?.[selected!.force];
    const d = force ? forceDisplacement(force.f0, frame!.a1 ?? [1, 1, 1], frame!.a2 ?? [1, 1, 1], force.region ?? [0, 1, 0, 1]) : null;
    if (d && handlePoints.length === 5) pointArrow(effect, handlePoints[4], d);
    else effect.visible = false;
  }

  /** An arrow's tail and tip (world points). */
  const ends = (arrow: THREE.ArrowHelper) => {
    const from = arrow.position.toArray() as Vec3;
    const tip = arrow.position.clone().addScaledVector(new THREE.Vector3(0, 1, 0).applyQuaternion(arrow.quaternion), arrow.cone.position.y);
    return { from, to: tip.toArray() as Vec3 };
  };

  /** The handle of the selected force under a client point, if any. */
  function handleAt(x: number, y: number): number | null {
    let best: number | null = null, bestD = HANDLE_PICK_PIXELS;
    handlePoints.forEach((p, i) => {
      const s = surfaceView.toClient(p);
      const d = Math.hypot(s.x - x, s.y - y);
      if (s.visible && d <= bestD) (best = i), (bestD = d);
    });
    return best;
  }

  /** The parameters on the gesture's patch of the surface point under a client point. */
  async function uvAt(frame: number, x: number, y: number): Promise<UV | null> {
    const hit = picker.hit(x, y);
    if (!hit) return null;
    const [uv] = await api.patchUv(frame, [hit.point.toArray() as Vec3], studio.solver);
    return uv;
  }

  /** Sets frame `f`'s forces (page copy and server, one undo step), selecting force `k`. */
  function setForces(f: number, forces: FrameForce[], k: number): void {
    store.update(['forces', 'selection'], (s) => {
      s.model!.frames[f].forces = forces;
      s.selectedFrames = new Set([f]);
      s.selectedForce = k;
    });
    const sent = structuredClone(forces);
    void pump.once('force', () => ({ op: 'set-forces', frame: f, forces: sent }));
  }

  const container = surfaceView.container;
  container.addEventListener(
    'pointerdown',
    (ev) => {
      const model = store.state.model;
      if (ev.button !== 0 || !model || gesture) return;
      const handle = handleAt(ev.clientX, ev.clientY);
      let frame: Promise<number | null>;
      let force = -1;
      let start: Region;
      if (handle !== null && handleOf) {
        frame = Promise.resolve(handleOf.frame);
        force = handleOf.force;
        start = handleOf.region;
      } else if (drawing && !ev.shiftKey && !ev.ctrlKey) {
        const hit = picker.hit(ev.clientX, ev.clientY);
        if (!hit) return;
        frame = picker.frameOf(hit.triangle);
        start = [0, 0, 0, 0];
      } else return;
      ev.stopPropagation(); // neither the orbit controls nor the frame picking
      ev.preventDefault();
      container.setPointerCapture(ev.pointerId);
      const x = ev.clientX, y = ev.clientY;
      const g: Gesture = { pointer: ev.pointerId, frame: -1, force, handle: handle ?? -1, start, region: start, asked: 0, from: Promise.resolve(null), x, y };
      g.from = frame.then((f) => {
        if (f === null) return null;
        g.frame = f;
        if (handle === CENTRE_HANDLE) return [(start[0] + start[1]) / 2, (start[2] + start[3]) / 2] as UV;
        return handle !== null ? regionCorners(start)[handle] : uvAt(f, x, y);
      });
      gesture = g;
    },
    true,
  );

  /** The gesture's region with the pointer at a client point. */
  async function follow(g: Gesture, x: number, y: number): Promise<void> {
    const asked = ++g.asked;
    const from = await g.from;
    if (!from || g.frame < 0) return;
    const to = await uvAt(g.frame, x, y);
    if (!to || asked !== g.asked || gesture !== g) return;
    g.region =
      g.handle === CENTRE_HANDLE ? moveRegion(g.start, from, to) : g.handle >= 0 ? resizeRegion(g.start, g.handle, to) : regionFromCorners(from, to);
    await redraw();
  }

  container.addEventListener(
    'pointermove',
    (ev) => {
      if (!gesture || ev.pointerId !== gesture.pointer) return;
      ev.stopPropagation();
      void follow(gesture, ev.clientX, ev.clientY);
    },
    true,
  );

  const end = (ev: PointerEvent) => {
    const g = gesture;
    if (!g || ev.pointerId !== g.pointer) return;
    ev.stopPropagation();
    container.releasePointerCapture(ev.pointerId);
    void studio.run(async () => {
      try {
        await follow(g, ev.clientX, ev.clientY);
      } finally {
        gesture = null;
      }
      const model = store.state.model;
      const clicked = Math.hypot(ev.clientX - g.x, ev.clientY - g.y) < CLICK_PIXELS;
      if (!model || g.frame < 0 || clicked || g.region.every((x, i) => x === g.start[i])) {
        await redraw();
        return;
      }
      const forces = [...(model.frames[g.frame].forces ?? [])];
      if (g.force < 0) forces.push({ f0: [0, 0, 0], region: g.region });
      else forces[g.force] = { ...forces[g.force], region: g.region };
      setForces(g.frame, forces, g.force < 0 ? forces.length - 1 : g.force);
    });
  };
  container.addEventListener('pointerup', end, true);
  container.addEventListener('pointercancel', end, true);

  return {
    toggleDraw,
    drawn: () => drawn,
    effect: () => (effect.visible ? ends(effect) : null),
    sharedEffects: () => sharedShown.flatMap((frame, i) => (sharedArrows[i].visible ? [{ frame, ...ends(sharedArrows[i]) }] : [])),
    handleScreen(h) {
      const p = handlePoints[h];
      if (!p) return null;
      const s = surfaceView.toClient(p);
      return { x: s.x, y: s.y };
    },
    async uvScreen(frame, uv) {
      const [p] = await api.patchPoints(frame, [uv], studio.solver);
      const s = surfaceView.toClient(new THREE.Vector3(...p));
      return { x: s.x, y: s.y };
    },
  };
}
