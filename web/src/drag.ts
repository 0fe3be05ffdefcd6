// The frame view's pointer tool: press a handle and drag to move its vertex, or the whole
// vertex selection when the handle is part of it (one undo group per drag); shift+click a
// handle adds or removes it, ctrl+click removes it; shift+drag on empty space selects the
// vertices in a box (ctrl+drag removes them); click a frame's outline to select it (shift or
// ctrl adds or removes), click empty space to clear the selection. Installed before the orbit
// controls, so a press the tool takes never orbits.
import type { Vec3 } from './api';
import { $ } from './dom';
import { evaluateExpression } from './input';
import type { Topic } from './store';
import type { Studio } from './studio';
import type { Viewport } from './viewport';
import { coincidentWith, toggled, toggledInStack } from './structure';
import { nearestOnSegments, nearestVertex, onAxisTo, onSurface, outlineSegments, snapped, surfaceSnapshot, TYPED_CHARACTERS, typedOffset } from './snap';
import type { SnapMode } from './snap';
import type * as THREE from 'three';
import { mirrorPartners, symmetricMove, symmetryPlane } from './symmetry';
import type { MirrorPlane } from './symmetry';
import { GLOBAL_BASIS, isGlobal, selectionBasis } from './orientation';
import type { Basis, Orientation } from './orientation';

/** The panel's transform orientation (*axes*). */
export const orientationChoice = () => ($<HTMLSelectElement>('orientation').value || 'global') as Orientation;

/** The axes of the panel's orientation for the vertices `vertices` (the selection a tool acts
 * on; the selected frames and the active vertex from the store). Global costs nothing; the
 * others are computed where a tool starts (a drag's press, a gizmo shown), never per step. */
export function studioBasis(studio: Studio, vertices: readonly number[]): Basis {
  const s = studio.store.state;
  const orientation = orientationChoice();
  if (orientation === 'global' || !s.model) return GLOBAL_BASIS;
  return selectionBasis(orientation, {
    model: s.model,
    vertices,
    frames: [...s.selectedFrames],
    active: s.selectedVertex,
    mesh: s.mesh,
  });
}

/** An axis' name in the status line: x, or local x / normal z. */
export const axisName = (axis: number, basis: Basis) => `${isGlobal(basis) ? '' : `${orientationChoice()} `}${'xyz'[axis]}`;

/** Puts each vertex of `moved` at its start `from[i]` offset by `d` in the store (one update,
 * announcing `topics`), and moves the frame view's handles of those but `skip` (a handle the
 * store's 'vertex' subscriber moves itself). */
function offsetVertices(
  studio: Studio,
  moved: readonly number[],
  from: readonly Vec3[],
  d: readonly [number, number, number],
  topics: Topic[],
  skip: number | null = null,
): void {
  placeVertices(studio, moved, (i) => [from[i][0] + d[0], from[i][1] + d[1], from[i][2] + d[2]], topics, skip);
}

/** Puts each vertex `moved[i]` at `at(i)` in the store (one update, announcing `topics`) and
 * moves the frame view's handles of those but `skip`. */
export function placeVertices(studio: Studio, moved: readonly number[], at: (i: number) => Vec3, topics: Topic[], skip: number | null): void {
  const { store, frameView } = studio;
  store.update(topics, (s) => {
    moved.forEach((v, i) => (s.model!.vertices[v] = at(i)));
  });
  for (const v of moved) if (v !== skip) frameView.moveVertex(v, store.state.model!.vertices[v]);
}

/** Presses that move less than this many pixels are clicks. */
const CLICK_PIXELS = 5;
/** Above this many vertices the hover cursor is not computed (picking costs per move). */
const HOVER_MAX_VERTICES = 20000;

/** The handle drag, for the views that start one (the frame view here, the surface view in
 * modeller.ts): the grabbed vertex moves in the plane through it facing that view's camera. */
export interface DragTool {
  /** Grabs `vertex` (and the selection it belongs to) for the pointer of `ev` in `view`. */
  begin(view: Viewport, vertex: number, ev: PointerEvent): void;
  /** Whether a drag of this pointer is in progress. */
  dragging(pointer: number): boolean;
  /** The pointer moved (a drag's step). */
  move(ev: PointerEvent): void;
  /** The pointer was released: the drag's gesture ends (one undo step). */
  end(ev: PointerEvent): Promise<void>;
}

export function mountDragTool(studio: Studio): DragTool {
  const { store, frameView, pump } = studio;
  const canvas = frameView.renderer.domElement;
  /** A drag: the handle grabbed, and every vertex it moves with where it started. */
  let drag: {
    vertex: number;
    pointer: number;
    moved: number[];
    from: Vec3[];
    /** The locked axis (X, Y, Z keys), or null: in the plane facing the camera. */
    axis: 0 | 1 | 2 | null;
    /** The axes X, Y, Z lock to and the step rounds along (the panel's orientation, taken at
     * the press). */
    basis: Basis;
    /** Where the pointer was last. */
    at?: { x: number; y: number };
    /** The view the drag is in (its camera's plane). */
    view: Viewport;
    /** Symmetry on: the mirror plane, and what mirrorPartners found at the start. */
    mirror: { plane: MirrorPlane; found: ReturnType<typeof mirrorPartners> } | null;
    /** What the drag snaps to, taken at its start (what does not move with it). */
    snap:
      | { mode: 'vertices'; candidates: number[] }
      | { mode: 'edges'; segments: [number, number][] }
      | { mode: 'surface'; surface: THREE.Mesh }
      | null;
    /** The distance typed during the drag (as typed), or '' (the pointer places it). */
    typed: string;
  } | null = null;
  let press: { x: number; y: number; shift: boolean; ctrl: boolean } | null = null;
  let box: { x: number; y: number; pointer: number; remove: boolean; div: HTMLDivElement } | null = null;

  const selectVertices = (vertices: number[]) =>
    store.update(['selection'], (s) => {
      s.selectedVertices = vertices;
      s.selectedVertex = vertices.length ? vertices[vertices.length - 1] : null;
    });

  const tool: DragTool = {
    begin(view, vertex, ev) {
      const model = store.state.model;
      if (!model) return;
      view.controls.enabled = false; // the views' listeners run before their controls'
      const current = store.state.selectedVertices;
      const moved = current.includes(vertex) && current.length > 1 ? [...current] : [vertex];
      if (moved.length === 1) selectVertices([vertex]);
      const from = moved.map((v) => [...model.vertices[v]] as Vec3);
      const plane = symmetryPlane($<HTMLSelectElement>('symmetry').value, model.vertices);
      const mirror = plane && { plane, found: mirrorPartners(model.vertices, moved, from, plane) };
      drag = { vertex, pointer: ev.pointerId, moved, from, axis: null, basis: studioBasis(studio, moved), view, mirror, snap: snapTargets(new Set([...moved, ...(mirror?.found.partners ?? [])])), typed: '' };
      studio.beginGesture('drag');
      ev.preventDefault();
    },
    dragging: (pointer) => !!drag && drag.pointer === pointer,
    move(ev) {
      if (!drag || ev.pointerId !== drag.pointer || !store.state.model) return;
      drag.at = { x: ev.clientX, y: ev.clientY };
      dragTo(ev.clientX, ev.clientY);
    },
    async end(ev) {
      if (!drag || ev.pointerId !== drag.pointer) return;
      drag.view.controls.enabled = true;
      drag = null;
      await studio.endGesture();
    },
  };

  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button !== 0 || !store.state.model) return;
    const model = store.state.model;
    const modifier = ev.shiftKey || ev.ctrlKey || ev.metaKey;
    const vertex = frameView.vertexAt(ev.clientX, ev.clientY);
    if (vertex !== null && modifier) {
      frameView.controls.enabled = false; // this listener runs before the controls'
      const stack = coincidentWith(model, vertex);
      selectVertices(toggledInStack(store.state.selectedVertices, vertex, stack, ev.shiftKey ? 'toggle' : 'remove'));
      ev.preventDefault();
      return;
    }
    if (vertex !== null) {
      tool.begin(frameView, vertex, ev);
      canvas.setPointerCapture(ev.pointerId);
    } else if (modifier) {
      frameView.controls.enabled = false;
      const div = document.createElement('div');
      div.className = 'select-box';
      div.dataset.testid = 'select-box';
      document.body.append(div);
      box = { x: ev.clientX, y: ev.clientY, pointer: ev.pointerId, remove: !ev.shiftKey, div };
      // A box that is never dragged open is a click: shift or ctrl+click on a frame's outline.
      press = { x: ev.clientX, y: ev.clientY, shift: ev.shiftKey, ctrl: ev.ctrlKey || ev.metaKey };
      canvas.setPointerCapture(ev.pointerId);
      ev.preventDefault();
    } else {
      press = { x: ev.clientX, y: ev.clientY, shift: ev.shiftKey, ctrl: ev.ctrlKey || ev.metaKey };
    }
  });

  canvas.addEventListener('pointermove', (ev) => {
    const model = store.state.model;
    if (box && ev.pointerId === box.pointer) {
      const { style } = box.div;
      style.left = `${Math.min(box.x, ev.clientX)}px`;
      style.top = `${Math.min(box.y, ev.clientY)}px`;
      style.width = `${Math.abs(ev.clientX - box.x)}px`;
      style.height = `${Math.abs(ev.clientY - box.y)}px`;
      return;
    }
    if (!drag && ev.buttons === 0 && model && model.vertices.length <= HOVER_MAX_VERTICES) {
      // The cursor tells what a press would do: grab a handle, select a frame, or orbit.
      const cursor =
        frameView.vertexAt(ev.clientX, ev.clientY) !== null
          ? 'grab'
          : frameView.frameAt(ev.clientX, ev.clientY) !== null
            ? 'pointer'
            : '';
      if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
    }
    tool.move(ev);
  });

  /** What a drag that moves `moving` snaps to: the panel's *snap drags to*, and the vertices,
   * outline segments or surface (as it is now) that stay put. */
  function snapTargets(moving: ReadonlySet<number>): NonNullable<typeof drag>['snap'] {
    const model = store.state.model!;
    const mode = $<HTMLSelectElement>('snap-to').value as SnapMode;
    if (mode === 'vertices') return { mode, candidates: model.vertices.map((_, v) => v).filter((v) => !moving.has(v)) };
    if (mode === 'edges') return { mode, segments: outlineSegments(model.frames, moving) };
    const mesh = store.state.mesh;
    if (mode === 'surface' && mesh) return { mode, surface: surfaceSnapshot(mesh.positions, mesh.indices) };
    return null;
  }

  /** The point the grabbed vertex snaps to for the pointer at (x, y), or null (none near). */
  function snapPoint(x: number, y: number): Vec3 | null {
    const snap = drag?.snap;
    if (!drag || !snap) return null;
    const vertices = store.state.model!.vertices;
    if (snap.mode === 'vertices') {
      const v = nearestVertex(vertices, snap.candidates, drag.view, x, y);
      return v === null ? null : ([...vertices[v]] as Vec3);
    }
    if (snap.mode === 'edges') return nearestOnSegments(vertices, snap.segments, drag.view, x, y);
    return onSurface(snap.surface, drag.view, x, y);
  }

  /** Moves the dragged vertices for the pointer at (x, y): in the plane facing the camera, or
   * along the locked axis of the drag's basis (the point of the axis through the start
   * nearest the pointer's ray). A typed distance sets the offset's length (along the axis, or
   * the pointer's direction); else a snap target near the pointer places the grabbed vertex
   * on it (with an axis locked: where the target lies along the axis); else the offset is
   * rounded to the grid step along the basis' axes when one is set. */
  function dragTo(x: number, y: number): void {
    if (!drag) return;
    const { vertex, moved, from } = drag;
    const start = from[moved.indexOf(vertex)];
    const along = drag.axis === null ? null : drag.basis[drag.axis];
    const target = along === null ? drag.view.dragTarget(start, x, y) : drag.view.axisTarget(start, along, x, y);
    if (!target) return;
    const free: [number, number, number] = [target[0] - start[0], target[1] - start[1], target[2] - start[2]];
    const typed = drag.typed ? evaluateExpression(drag.typed) : null;
    const snap = typed === null ? snapPoint(x, y) : null;
    const d =
      typed !== null && Number.isFinite(typed)
        ? typedOffset(typed, along, free)
        : snap
          ? along
            ? onAxisTo(start, along, snap)
            : ([snap[0] - start[0], snap[1] - start[1], snap[2] - start[2]] as Vec3)
          : snapped(free, snapStep(), isGlobal(drag.basis) ? null : drag.basis);
    if (!d) return;
    const skip = store.state.selectedVertex;
    const mirror = drag.mirror;
    let all = moved;
    if (!mirror) {
      offsetVertices(studio, moved, from, d, ['vertex'], skip);
    } else {
      // Symmetry: vertices on the plane stay on it, partners go to the mirror images.
      const to = from.map((p) => [p[0] + d[0], p[1] + d[1], p[2] + d[2]] as Vec3);
      const move = symmetricMove(mirror.plane, mirror.found, moved, to);
      all = move.vertices;
      placeVertices(studio, all, (i) => move.positions[i], ['vertex'], skip);
    }
    const position = (v: number) => [...store.state.model!.vertices[v]] as Vec3;
    pump.push(() =>
      all.length === 1
        ? { op: 'move-vertex', vertex, position: position(vertex) }
        : { op: 'move-vertices', vertices: all, positions: all.map(position) },
    );
  }

  /** The grid step of the panel's Snap box; 0 (off) when empty or not a number above 0. */
  const snapStep = () => {
    const step = evaluateExpression($<HTMLInputElement>('snap-step').value.trim());
    return step !== null && step > 0 && Number.isFinite(step) ? step : 0;
  };

  // During a drag, as in Blender (the keys are the drag's, not the shortcuts': taken before
  // keys.ts sees them): X, Y or Z locks it to that axis (again: free again); a number typed
  // sets the distance (Backspace edits it), Enter applies it and ends the drag.
  document.addEventListener(
    'keydown',
    (ev) => {
      if (!drag || ev.ctrlKey || ev.metaKey || ev.altKey) return;
      const k = ['x', 'y', 'z'].indexOf(ev.key.toLowerCase());
      const typing = TYPED_CHARACTERS.test(ev.key) || (ev.key === 'Backspace' && drag.typed !== '');
      if (k < 0 && !typing && ev.key !== 'Enter') return;
      ev.preventDefault();
      ev.stopImmediatePropagation();
      if (k >= 0) {
        drag.axis = drag.axis === k ? null : (k as 0 | 1 | 2);
        studio.say(drag.axis === null ? 'drag: free' : `drag: along ${axisName(drag.axis, drag.basis)} only`);
      } else if (typing) {
        drag.typed = ev.key === 'Backspace' ? drag.typed.slice(0, -1) : drag.typed + ev.key;
        const value = evaluateExpression(drag.typed);
        studio.say(drag.typed ? `drag: distance ${drag.typed}${value === null ? ' (not a number yet)' : ''}; Enter applies` : 'drag: free');
      }
      if (drag.at) dragTo(drag.at.x, drag.at.y);
      if (ev.key === 'Enter') void tool.end({ pointerId: drag.pointer } as PointerEvent);
    },
    true,
  );

  async function endPress(ev: PointerEvent): Promise<void> {
    if (tool.dragging(ev.pointerId)) return tool.end(ev);
    if (box && ev.pointerId === box.pointer) {
      const opened = Math.hypot(ev.clientX - box.x, ev.clientY - box.y) >= CLICK_PIXELS;
      if (opened) {
        const inside = frameView.verticesInBox(box.x, box.y, ev.clientX, ev.clientY);
        let next = [...store.state.selectedVertices];
        for (const v of inside) next = toggled(next, v, box.remove ? 'remove' : 'add');
        selectVertices(next);
        press = null;
      }
      box.div.remove();
      box = null;
      frameView.controls.enabled = true;
      if (opened) return;
    }
    frameView.controls.enabled = true;
    if (press && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) < CLICK_PIXELS) {
      const frame = frameView.frameAt(ev.clientX, ev.clientY);
      const adding = press.shift || press.ctrl;
      store.update(['selection', 'forces'], (s) => {
        if (frame === null) {
          if (!adding) s.selectedFrames = new Set();
        } else if (adding) {
          const next = new Set(s.selectedFrames);
          if (next.has(frame)) next.delete(frame);
          else next.add(frame);
          s.selectedFrames = next;
        } else {
          s.selectedFrames = new Set([frame]);
        }
        if (frame === null && !adding) {
          s.selectedVertex = null;
          s.selectedVertices = [];
        }
        s.selectedForce = 0;
      });
    }
    press = null;
  }
  canvas.addEventListener('pointerup', (ev) => void endPress(ev));
  canvas.addEventListener('pointercancel', (ev) => void endPress(ev));
  return tool;
}
