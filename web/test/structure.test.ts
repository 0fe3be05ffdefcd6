// The modeller's edits from the selection: which sides are boundary edges, which the
// selection names, and what each tool asks for when the selection does not fit.
import { describe, expect, it } from 'vitest';
import type { Model } from '../src/api';
import { addFrameEdit, boundarySides, extrudeEdit, framesEdit, mirrorEdit, selectAll, selectInverse, selectLinked, selectStrip, selectedBoundarySides, splitEdit, toggled, toggledInStack, weldEdit } from '../src/structure';

/** Two frames side by side on a 5 × 3 lattice (vertex j * 5 + i), sharing the column i = 2. */
function twoFrames(): Model {
  const vertices: [number, number, number][] = [];
  for (let j = 0; j < 3; ++j) for (let i = 0; i < 5; ++i) vertices.push([i, j, 0]);
  const at = (i: number, j: number) => j * 5 + i;
  const frame = (i: number) => ({
    vertices: [at(i, 0), at(i + 1, 0), at(i + 2, 0), at(i + 2, 1), at(i + 2, 2), at(i + 1, 2), at(i, 2), at(i, 1)],
  });
  return { type: 'vertex-frames', vertices, frames: [frame(0), frame(2)] };
}

describe('structure edits from the selection', () => {
  it('finds the boundary sides: all but the shared one', () => {
    const sides = boundarySides(twoFrames());
    expect(sides).toHaveLength(6);
    expect(sides).not.toContainEqual({ frame: 0, side: 1 });
    expect(sides).not.toContainEqual({ frame: 1, side: 3 });
  });

  it('names the boundary sides whose corners are selected, never the shared side', () => {
    const m = twoFrames();
    expect(selectedBoundarySides(m, [4, 14])).toEqual([{ frame: 1, side: 1 }]);
    expect(selectedBoundarySides(m, [2, 12])).toEqual([]); // shared: not a boundary edge
    expect(selectedBoundarySides(m, [0, 2, 4])).toEqual([{ frame: 0, side: 0 }, { frame: 1, side: 0 }]);
    expect(extrudeEdit(m, [0, 2, 4])).toEqual({ edit: { op: 'extrude', edges: [{ frame: 0, side: 0 }, { frame: 1, side: 0 }] } });
    expect(extrudeEdit(m, [7])).toHaveProperty('problem', expect.stringMatching(/^Extrude: select both corners/));
  });

  it('welds two vertices in pick order, or two boundary edges', () => {
    const m = twoFrames();
    expect(weldEdit(m, [14, 0])).toEqual({ edit: { op: 'weld-vertices', vertices: [14, 0] } });
    expect(weldEdit(m, [0, 10, 4, 14])).toEqual({ edit: { op: 'weld-edges', edges: [{ frame: 0, side: 3 }, { frame: 1, side: 1 }] } });
    expect(weldEdit(m, [0, 1, 2])).toHaveProperty('problem', expect.stringContaining('3 vertices'));
  });

  it('needs 4 corners for a frame, some frames to split, delete or flip', () => {
    expect(addFrameEdit([1, 2, 3, 4])).toEqual({ edit: { op: 'add-frame', corners: [1, 2, 3, 4] } });
    expect(addFrameEdit([1, 2, 3])).toHaveProperty('problem', expect.stringContaining('(3 selected)'));
    expect(splitEdit(new Set([1]), 'u')).toEqual({ edit: { op: 'split-frame', frames: [1], parts: 2, across: 'u' } });
    expect(splitEdit(new Set([1]), '4')).toEqual({ edit: { op: 'split-frame', frames: [1], parts: 4 } });
    // Several frames split in one edit, listed in order whatever the pick order.
    expect(splitEdit(new Set([3, 0]), '4')).toEqual({ edit: { op: 'split-frame', frames: [0, 3], parts: 4 } });
    expect(splitEdit(new Set(), 'v')).toHaveProperty('problem', expect.stringContaining('select frames first'));
    expect(framesEdit('delete-frames', new Set([2, 0]))).toEqual({ edit: { op: 'delete-frames', frames: [0, 2] } });
    expect(framesEdit('flip-frames', new Set())).toHaveProperty('problem', 'Flip: select frames first');
  });

  it('toggles a selection keeping the pick order', () => {
    expect(toggled([3, 1], 2, 'toggle')).toEqual([3, 1, 2]);
    expect(toggled([3, 1, 2], 1, 'toggle')).toEqual([3, 2]);
    expect(toggled([3, 1], 1, 'add')).toEqual([3, 1]);
    expect(toggled([3, 1], 3, 'remove')).toEqual([1]);
  });

  it('picks each of coincident vertices in turn (shift+click on the same spot)', () => {
    // Vertices 4 and 9 stand at one place; the pick finds 4 each time.
    expect(toggledInStack([], 4, [4, 9], 'toggle')).toEqual([4]);
    expect(toggledInStack([4], 4, [4, 9], 'toggle')).toEqual([4, 9]);
    expect(toggledInStack([4, 9], 4, [4, 9], 'toggle')).toEqual([9]);
    expect(toggledInStack([4, 9], 4, [4, 9], 'remove')).toEqual([4]);
    expect(toggledInStack([2], 5, [5], 'toggle')).toEqual([2, 5]);
    expect(toggledInStack([2, 5], 5, [5], 'toggle')).toEqual([2]);
  });
});

describe('selection tools', () => {
  // Two frames sharing a side (vertices 0..12) and a third apart (13..20).
  const frame = (v: number[]) => ({ vertices: v });
  const model = {
    vertices: Array.from({ length: 21 }, (_, i) => [i, 0, 0] as [number, number, number]),
    frames: [frame([0, 1, 2, 3, 4, 5, 6, 7]), frame([2, 8, 9, 10, 11, 12, 4, 3]), frame([13, 14, 15, 16, 17, 18, 19, 20])],
  } as unknown as Model;

  it('selects all, the inverse, and what is linked', () => {
    const all = selectAll(model);
    expect(all.vertices).toHaveLength(21);
    expect([...all.frames]).toEqual([0, 1, 2]);
    const inverse = selectInverse(model, { vertices: [0, 1], frames: new Set([2]) });
    expect(inverse.vertices).toHaveLength(19);
    expect(inverse.vertices).not.toContain(0);
    expect([...inverse.frames]).toEqual([0, 1]);
    const linked = selectLinked(model, { vertices: [9], frames: new Set() });
    expect([...linked.frames].sort()).toEqual([0, 1]);
    expect(linked.vertices[0]).toBe(9); // the pick order kept first
    expect([...linked.vertices].sort((a, b) => a - b)).toEqual(Array.from({ length: 13 }, (_, i) => i));
  });
});

/** A tube of `round` frames round z and `along` frames up it, on a lattice of 2 round × (2
 * along + 1) points (vertex j * 2 round + i); frame (a, b) is frame b * round + a. With `flip`,
 * frame 1 of each row has its u reversed (P1..P8 mirrored), as after Flip. */
function tube(round: number, along: number, flip = false): Model {
  const cols = 2 * round;
  const vertices: [number, number, number][] = [];
  for (let j = 0; j <= 2 * along; ++j)
    for (let i = 0; i < cols; ++i) vertices.push([Math.cos((2 * Math.PI * i) / cols), Math.sin((2 * Math.PI * i) / cols), j]);
  const at = (i: number, j: number) => j * cols + (i % cols);
  const frames = [];
  for (let b = 0; b < along; ++b)
    for (let a = 0; a < round; ++a) {
      const [i, j] = [2 * a, 2 * b];
      let ring = [at(i, j), at(i + 1, j), at(i + 2, j), at(i + 2, j + 1), at(i + 2, j + 2), at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)];
      if (flip && a === 1) ring = [ring[2], ring[1], ring[0], ring[7], ring[6], ring[5], ring[4], ring[3]];
      frames.push({ vertices: ring });
    }
  return { type: 'vertex-frames', vertices, frames };
}

describe('loop and ring select', () => {
  it('loop: the row of frames round the tube through the selected frame; ring: its column', () => {
    const m = tube(4, 3);
    const sorted = (p: { frames: Set<number> }) => [...p.frames].sort((a, b) => a - b);
    expect(sorted(selectStrip(m, { vertices: [], frames: new Set([5]) }, 'u'))).toEqual([4, 5, 6, 7]);
    expect(sorted(selectStrip(m, { vertices: [], frames: new Set([5]) }, 'v'))).toEqual([1, 5, 9]);
    // Two frames: both rows.
    expect(sorted(selectStrip(m, { vertices: [], frames: new Set([0, 9]) }, 'u'))).toEqual([0, 1, 2, 3, 8, 9, 10, 11]);
    // The vertices come with the frames: the middle row's 3 rows of lattice points less its
    // 4 centres.
    const loop = selectStrip(m, { vertices: [], frames: new Set([5]) }, 'u');
    expect(loop.vertices).toHaveLength(3 * 8 - 4);
  });

  it('runs on through a frame whose u runs the other way, and stops at a boundary', () => {
    const m = tube(4, 3, true);
    const sorted = (p: { frames: Set<number> }) => [...p.frames].sort((a, b) => a - b);
    expect(sorted(selectStrip(m, { vertices: [], frames: new Set([4]) }, 'u'))).toEqual([4, 5, 6, 7]);
    expect(sorted(selectStrip(m, { vertices: [], frames: new Set([5]) }, 'v'))).toEqual([1, 5, 9]);
    // A flat row of two frames: the strip ends at the sides no other frame shares.
    expect(sorted(selectStrip(twoFrames(), { vertices: [], frames: new Set([0]) }, 'u'))).toEqual([0, 1]);
    expect(sorted(selectStrip(twoFrames(), { vertices: [], frames: new Set([0]) }, 'v'))).toEqual([0]);
  });
});

describe('mirrorEdit', () => {
  it('copies across the chosen plane: at 0 as before, through the centre with its offset', () => {
    expect(mirrorEdit(new Set([1, 0]), { axis: 0, at: 0 })).toEqual({ edit: { op: 'mirror-frames', frames: [0, 1], axis: 'x' } });
    expect(mirrorEdit(new Set([0]), { axis: 2, at: 1.5 })).toEqual({ edit: { op: 'mirror-frames', frames: [0], axis: 'z', at: 1.5 } });
    expect('problem' in mirrorEdit(new Set([0]), null)).toBe(true);
    expect('problem' in mirrorEdit(new Set(), { axis: 0, at: 0 })).toBe(true);
  });
});
