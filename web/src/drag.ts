// The frame view's pointer tool: press a handle and drag to move its vertex (one undo
// group per drag), click a frame's outline to select it (shift adds or removes), click
// empty space to clear the selection. Installed before the orbit controls, so a press on
// a handle never orbits.
import type { Vec3 } from './api';
import type { Studio } from './studio';

/** Presses that move less than this many pixels are clicks. */
const CLICK_PIXELS = 5;
/** Above this many vertices the hover cursor is not computed (picking costs per move). */
const HOVER_MAX_VERTICES = 20000;

export function mountDragTool(studio: Studio): void {
  const { store, frameView, pump } = studio;
  const canvas = frameView.renderer.domElement;
  let drag: { vertex: number; pointer: number } | null = null;
  let press: { x: number; y: number; shift: boolean } | null = null;

  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button !== 0 || !store.state.model) return;
    const vertex = frameView.vertexAt(ev.clientX, ev.clientY);
    if (vertex !== null) {
      frameView.controls.enabled = false; // this listener runs before the controls'
      drag = { vertex, pointer: ev.pointerId };
      canvas.setPointerCapture(ev.pointerId);
      store.update(['selection'], (s) => (s.selectedVertex = vertex));
      studio.beginGesture('drag');
      ev.preventDefault();
    } else {
      press = { x: ev.clientX, y: ev.clientY, shift: ev.shiftKey };
    }
  });

  canvas.addEventListener('pointermove', (ev) => {
    const model = store.state.model;
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
    if (!drag || ev.pointerId !== drag.pointer || !model) return;
    const vertex = drag.vertex;
    const target = frameView.dragTarget(model.vertices[vertex], ev.clientX, ev.clientY);
    if (!target) return;
    store.update(['vertex'], (s) => (s.model!.vertices[vertex] = target));
    pump.push(() => ({ op: 'move-vertex', vertex, position: [...store.state.model!.vertices[vertex]] as Vec3 }));
  });

  async function endPress(ev: PointerEvent): Promise<void> {
    if (drag && ev.pointerId === drag.pointer) {
      drag = null;
      frameView.controls.enabled = true;
      await studio.endGesture();
      return;
    }
    if (press && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) < CLICK_PIXELS) {
      const frame = frameView.frameAt(ev.clientX, ev.clientY);
      const shift = press.shift;
      store.update(['selection', 'forces'], (s) => {
        if (frame === null) {
          if (!shift) s.selectedFrames = new Set();
        } else if (shift) {
          const next = new Set(s.selectedFrames);
          if (next.has(frame)) next.delete(frame);
          else next.add(frame);
          s.selectedFrames = next;
        } else {
          s.selectedFrames = new Set([frame]);
        }
        if (frame === null && !shift) s.selectedVertex = null;
        s.selectedForce = 0;
      });
    }
    press = null;
  }
  canvas.addEventListener('pointerup', (ev) => void endPress(ev));
  canvas.addEventListener('pointercancel', (ev) => void endPress(ev));
}
