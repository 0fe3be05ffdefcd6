// The modeller's structure edits made from the selection (no DOM: web/test runs it in
// Node). Sides are numbered as the server and GET /api/boundaries number them: 0 v = 0,
// 1 u = 1, 2 v = 1, 3 u = 0 (include/pdesurf/session.hpp).
import type { Edit, Model } from './api';
import type { MirrorPlane } from './symmetry';

/** A side of a frame. */
export interface FrameSide {
  frame: number;
  side: number;
}

/** The vertex slots (into Frame.vertices) of each side: start, middle, end. */
export const SIDE_SLOTS = [
  [0, 1, 2],
  [2, 3, 4],
  [6, 5, 4],
  [0, 7, 6],
] as const;

const sideKey = (v: readonly number[]) => {
  const [a, m, b] = v[0] <= v[2] ? v : [v[2], v[1], v[0]];
  return `${a}/${m}/${b}`;
};

/** The sides run by one frame only (a side whose three vertices are one point is no edge). */
export function boundarySides(model: Model): FrameSide[] {
  const count = new Map<string, number>();
  const all: { side: FrameSide; key: string }[] = [];
  model.frames.forEach((frame, f) => {
    for (let s = 0; s < 4; ++s) {
      const v = SIDE_SLOTS[s].map((i) => frame.vertices[i]);
      if (v[0] === v[1] && v[1] === v[2]) continue;
      const key = sideKey(v);
      count.set(key, (count.get(key) ?? 0) + 1);
      all.push({ side: { frame: f, side: s }, key });
    }
  });
  return all.filter((e) => count.get(e.key) === 1).map((e) => e.side);
}

/** The boundary sides whose two corners are both selected. */
export function selectedBoundarySides(model: Model, selected: readonly number[]): FrameSide[] {
  const picked = new Set(selected);
  return boundarySides(model).filter(({ frame, side }) => {
    const v = model.frames[frame].vertices;
    return picked.has(v[SIDE_SLOTS[side][0]]) && picked.has(v[SIDE_SLOTS[side][2]]);
  });
}

/** What a structure tool needs selected, said to the user when it is missing. */
export type Made = { edit: Edit } | { problem: string };

export function extrudeEdit(model: Model, selected: readonly number[]): Made {
  const edges = selectedBoundarySides(model, selected);
  if (!edges.length)
    return { problem: 'Extrude: select both corners of one or more boundary edges (box-select or shift+click)' };
  return { edit: { op: 'extrude', edges } };
}

export function addFrameEdit(selected: readonly number[]): Made {
  if (selected.length !== 4)
    return { problem: `Add frame: select 4 corner vertices in turn round the new frame (${selected.length} selected)` };
  return { edit: { op: 'add-frame', corners: [...selected] } };
}

export function weldEdit(model: Model, selected: readonly number[]): Made {
  if (selected.length === 2) return { edit: { op: 'weld-vertices', vertices: [selected[0], selected[1]] } };
  const edges = selectedBoundarySides(model, selected);
  if (edges.length === 2) return { edit: { op: 'weld-edges', edges } };
  return {
    problem: `Weld: select 2 vertices, or the corners of 2 boundary edges (${selected.length} vertices, ${edges.length} boundary edges selected)`,
  };
}

export function framesEdit(op: 'delete-frames' | 'flip-frames', frames: ReadonlySet<number>): Made {
  if (!frames.size) return { problem: `${op === 'delete-frames' ? 'Delete' : 'Flip'}: select frames first` };
  return { edit: { op, frames: [...frames].sort((a, b) => a - b) } };
}

/** Copies the selected frames across the panel's symmetry plane (x, y or z = 0, or through the
 * model's centre: symmetryPlane in symmetry.ts; null when off), welded at the seam. */
export function mirrorEdit(selected: ReadonlySet<number>, plane: MirrorPlane | null): Made {
  if (!plane) return { problem: 'Mirror: choose the symmetry plane in the panel first' };
  if (!selected.size) return { problem: 'Mirror: select frames first' };
  const axis = (['x', 'y', 'z'] as const)[plane.axis];
  const frames = [...selected].sort((a, b) => a - b);
  return { edit: plane.at === 0 ? { op: 'mirror-frames', frames, axis } : { op: 'mirror-frames', frames, axis, at: plane.at } };
}

/** Splits the selected frames (all of them at once: one undo step); each cut runs on through
 * the neighbours across the edges it crosses, so the model stays one without gaps. */
export function splitEdit(selected: ReadonlySet<number>, parts: '4' | 'u' | 'v'): Made {
  if (!selected.size) return { problem: 'Split: select frames first (Ctrl+A: all)' };
  const frames = [...selected].sort((a, b) => a - b);
  return { edit: parts === '4' ? { op: 'split-frame', frames, parts: 4 } : { op: 'split-frame', frames, parts: 2, across: parts } };
}

/** A click's selection change on a handle that may stand on others (coincident vertices, a
 * weld's two sides): `item` is the handle picked and the stack every vertex at its place.
 * Shift+click (`toggle`) adds the first of the stack not yet selected, so that repeated
 * shift+clicks pick each in turn, and removes `item` only when the whole stack is selected;
 * ctrl+click (`remove`) removes the last selected of the stack. */
export function toggledInStack(
  list: readonly number[],
  item: number,
  stack: readonly number[],
  mode: 'remove' | 'toggle',
): number[] {
  const inStack = stack.includes(item) ? stack : [item, ...stack];
  if (mode === 'toggle') {
    const free = inStack.find((v) => !list.includes(v));
    return free === undefined ? toggled(list, item, 'remove') : toggled(list, free, 'add');
  }
  const picked = list.filter((v) => inStack.includes(v));
  return picked.length ? toggled(list, picked[picked.length - 1], 'remove') : [...list];
}

/** The vertices standing exactly where vertex `v` stands (itself first). */
export function coincidentWith(model: Model, v: number): number[] {
  const p = model.vertices[v];
  const out = [v];
  model.vertices.forEach((q, i) => {
    if (i !== v && q[0] === p[0] && q[1] === p[1] && q[2] === p[2]) out.push(i);
  });
  return out;
}

/** A selection toggled: `item` added, or removed when `remove` (or, with `toggle`, when present). */
export function toggled(list: readonly number[], item: number, mode: 'add' | 'remove' | 'toggle'): number[] {
  const has = list.includes(item);
  if (mode === 'add' || (mode === 'toggle' && !has)) return has ? [...list] : [...list, item];
  return list.filter((x) => x !== item);
}

/** A selection of vertices (in pick order) and frames. */
export interface Picked {
  vertices: number[];
  frames: Set<number>;
}

/** Every vertex a frame uses, and every frame (select all). */
export function selectAll(model: Model): Picked {
  const vertices = [...new Set(model.frames.flatMap((f) => f.vertices))].sort((a, b) => a - b);
  return { vertices, frames: new Set(model.frames.map((_, f) => f)) };
}

/** What is not selected: the vertices frames use and the frames (select inverse). */
export function selectInverse(model: Model, picked: Picked): Picked {
  const all = selectAll(model);
  return {
    vertices: all.vertices.filter((v) => !picked.vertices.includes(v)),
    frames: new Set([...all.frames].filter((f) => !picked.frames.has(f))),
  };
}

/** Everything joined to the selection through shared vertices (select linked): the frames
 * reached from the selected frames and from the frames of the selected vertices, frame to
 * frame across any vertex they share, and all their vertices. */
export function selectLinked(model: Model, picked: Picked): Picked {
  const framesOf = new Map<number, number[]>();
  model.frames.forEach((f, k) => f.vertices.forEach((v) => framesOf.set(v, [...(framesOf.get(v) ?? []), k])));
  const reached = new Set<number>(picked.frames);
  for (const v of picked.vertices) for (const k of framesOf.get(v) ?? []) reached.add(k);
  const todo = [...reached];
  while (todo.length) {
    const k = todo.pop()!;
    for (const v of model.frames[k].vertices)
      for (const next of framesOf.get(v) ?? [])
        if (!reached.has(next)) reached.add(next), todo.push(next);
  }
  const vertices = new Set<number>(picked.vertices);
  for (const k of reached) for (const v of model.frames[k].vertices) vertices.add(v);
  return { vertices: [...picked.vertices, ...[...vertices].filter((v) => !picked.vertices.includes(v)).sort((a, b) => a - b)], frames: reached };
}

/** The strips of frames through the selected frames (loop and ring select): from each, frame
 * to frame across the sides u = 0 and u = 1 (`along` 'u': the loop) or v = 0 and v = 1 ('v':
 * the ring), each neighbour left by the side opposite the one it was entered by (so a
 * neighbour whose u runs another way continues the strip all the same), until a boundary or
 * back at the start (round a tube); with all their vertices. */
export function selectStrip(model: Model, picked: Picked, along: 'u' | 'v'): Picked {
  const sidesOf = new Map<string, FrameSide[]>();
  model.frames.forEach((frame, f) => {
    for (let s = 0; s < 4; ++s) {
      const key = sideKey(SIDE_SLOTS[s].map((i) => frame.vertices[i]));
      sidesOf.set(key, [...(sidesOf.get(key) ?? []), { frame: f, side: s }]);
    }
  });
  /** The frame across side `side` of frame `frame`, and the side it is entered by. */
  const across = (frame: number, side: number): FrameSide | null => {
    const key = sideKey(SIDE_SLOTS[side].map((i) => model.frames[frame].vertices[i]));
    return sidesOf.get(key)?.find((o) => o.frame !== frame) ?? null;
  };
  const reached = new Set<number>(picked.frames);
  const first = along === 'u' ? [1, 3] : [0, 2];
  for (const start of picked.frames)
    for (const side of first) {
      let at: FrameSide | null = { frame: start, side };
      while ((at = across(at.frame, at.side)) && !reached.has(at.frame)) {
        reached.add(at.frame);
        at = { frame: at.frame, side: (at.side + 2) % 4 };
      }
    }
  const vertices = new Set<number>(picked.vertices);
  for (const k of reached) for (const v of model.frames[k].vertices) vertices.add(v);
  return { vertices: [...picked.vertices, ...[...vertices].filter((v) => !picked.vertices.includes(v)).sort((a, b) => a - b)], frames: reached };
}
