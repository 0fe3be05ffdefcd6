// The modeller's structure edits made from the selection (no DOM: web/test runs it in
// Node). Sides are numbered as the server and GET /api/boundaries number them: 0 v = 0,
// 1 u = 1, 2 v = 1, 3 u = 0 (include/pdesurf/session.hpp).
import type { Edit, Model } from './api';

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

export function splitEdit(frames: ReadonlySet<number>, parts: '4' | 'u' | 'v'): Made {
  if (frames.size !== 1) return { problem: `Split: select one frame (${frames.size} selected)` };
  const [frame] = frames;
  return { edit: parts === '4' ? { op: 'split-frame', frame, parts: 4 } : { op: 'split-frame', frame, parts: 2, across: parts } };
}

/** A selection toggled: `item` added, or removed when `remove` (or, with `toggle`, when present). */
export function toggled(list: readonly number[], item: number, mode: 'add' | 'remove' | 'toggle'): number[] {
  const has = list.includes(item);
  if (mode === 'add' || (mode === 'toggle' && !has)) return has ? [...list] : [...list, item];
  return list.filter((x) => x !== item);
}
