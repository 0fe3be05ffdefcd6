// The shape editor's handles and edits (shape.ts): which points of a model file are handles,
// the edit a drag sends (absolute, so a drag's later steps replace its earlier ones), and the
// spine list a spine drag makes.
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { TANGENT_DRAW, curveEntries, curveMoveEdit, dragEdit, operatorOf, shapeHandles, spineWith } from '../src/shape';

const circle = (z: number, n = 5): Vec3[] =>
  Array.from({ length: n }, (_, j) => [Math.cos((2 * Math.PI * j) / n), Math.sin((2 * Math.PI * j) / n), z] as Vec3);

describe('handles', () => {
  it('are the points of position curves and the tips of tangents given as points, never a Fourier curve', () => {
    const model = {
      type: 'spectral',
      operator: 'ugail',
      N: 2,
      conditions: [
        { u: 0, curve: { points: circle(0) } },
        { u: 0, derivative: 1, curve: { points: circle(1) } },
        { u: 1, curve: { fourier: { a0: [0, 0, 1], a: [[1, 0, 0]] } } },
        { u: 1, derivative: 1, curve: { fourier: { a0: [0, 0, 2] } } },
      ],
    };
    const view = { curves: [], spines: [], spineHandles: { u: [0, 0.5, 1], points: [[0, 0, 0], [0, 0, 0.5], [0, 0, 1]] as Vec3[] } };
    const handles = shapeHandles(model, view);
    expect(handles.filter((h) => h.kind === 'curve').map((h) => h.kind === 'curve' && h.curve)).toEqual([0, 0, 0, 0, 0]);
    expect(handles.filter((h) => h.kind === 'spine')).toHaveLength(3);
    // The derivative condition's vectors: tips drawn from the position curve at the same u
    // (point j from point j), a drag sets the vector (tip - base) / TANGENT_DRAW.
    const tips = handles.filter((h) => h.kind === 'tangent' && h.curve === 1);
    expect(tips).toHaveLength(5);
    const tip = tips[2];
    if (tip.kind !== 'tangent') throw new Error('not a tangent');
    expect(tip.base).toEqual(circle(0)[2]);
    tip.p.forEach((x, c) => expect(x).toBeCloseTo(circle(0)[2][c] + TANGENT_DRAW * circle(1)[2][c], 15));
    expect(dragEdit(tip, [tip.base[0], tip.base[1], tip.base[2] + 0.5], [], null)).toEqual({
      op: 'move-curve-points',
      curve: 1,
      points: [2],
      positions: [[0, 0, 0.5 / TANGENT_DRAW]],
    });
    // The Fourier curve is listed for whole-curve transforms, centred on its a0; the
    // derivative conditions are vectors (no centre to move).
    const entries = curveEntries(model);
    expect(entries[2].centre).toEqual([0, 0, 1]);
    expect(entries[0].centre[2]).toBe(0);
    expect(entries.map((e) => e.vectors)).toEqual([false, true, false, true]);
    // A derivative condition of points whose position curve is Fourier: no tips (nowhere to
    // draw them from, point by point).
    const fourierBase = { ...model, conditions: [model.conditions[2], { u: 1, derivative: 1, curve: { points: circle(1) } }] };
    expect(shapeHandles(fourierBase, null).filter((h) => h.kind === 'tangent')).toHaveLength(0);
    // A Fourier derivative condition: one tip, its a0 (the mean tangent) drawn from the
    // position curve's a0; a drag sets a0.
    const mean = handles.find((h) => h.kind === 'tangent' && h.curve === 3);
    expect(mean).toEqual({ kind: 'tangent', curve: 3, point: 0, base: [0, 0, 1], p: [0, 0, 1 + TANGENT_DRAW * 2], mean: true });
    expect(dragEdit(mean!, [1, 0, 1.5], [], null)).toEqual({ op: 'set-fourier', curve: 3, a0: [1 / TANGENT_DRAW, 0, 0.5 / TANGENT_DRAW] });
  });

  it('a whole curve moves by a translation from the drag\'s start (absolute steps)', () => {
    expect(curveMoveEdit('uMin', [0, 0, 0.25])).toEqual({ op: 'transform-curve', curve: 'uMin', translate: [0, 0, 0.25], from: 'group-start' });
  });

  it('of a tangent row start on the side they leave, at their parameters', () => {
    // uMin along y at chord-length t; the tangent row's samples at t = 0, 0.25, 1.
    const uMin = { points: [[0, 0, 0], [0, 1, 0], [0, 4, 0]] };
    const model = {
      type: 'bspline-pde',
      boundary: { uMin, uMax: { points: [[4, 0, 0], [4, 4, 0]] }, vMin: { points: [[0, 0, 0], [4, 0, 0]] }, vMax: { points: [[0, 4, 0], [4, 4, 0]] }, uMinSecond: { tangent: { points: [[1, 0, 0], [1, 0, 1], [1, 0, 2]], t: [0, 0.25, 1] } } },
    };
    const tips = shapeHandles(model, null).filter((h) => h.kind === 'tangent');
    expect(tips.map((h) => h.kind === 'tangent' && h.base)).toEqual([[0, 0, 0], [0, 1, 0], [0, 4, 0]]);
    expect(tips[1].p).toEqual([TANGENT_DRAW, 1, TANGENT_DRAW]);
    expect(curveEntries(model).find((e) => e.ref === 'uMinSecond')?.vectors).toBe(true);
  });

  it('of a net are its given control points only', () => {
    const row = (i: number, inner: boolean): (Vec3 | null)[] =>
      Array.from({ length: 5 }, (_, j) => (inner && j >= 2 && j <= 3 ? null : ([i, j, 0] as Vec3)));
    const model = { type: 'bspline-pde', net: [row(0, false), row(1, false), row(2, true), row(3, true), row(4, false)] };
    const handles = shapeHandles(model, null);
    expect(handles).toHaveLength(25 - 4);
    expect(handles.every((h) => h.kind === 'control')).toBe(true);
    expect(dragEdit(handles[7], [9, 9, 9], [], null)).toEqual({ op: 'move-control-points', points: [[1, 2]], positions: [[9, 9, 9]] });
  });

  it('of the boundary form and the blends are their curves by name', () => {
    const pts = circle(0, 4);
    const boundary = { type: 'bspline-pde', boundary: { uMin: { bspline: pts }, uMax: { points: pts }, vMin: { bspline: pts }, vMax: { bspline: pts }, uMinSecond: { points: pts }, vMinSecond: { tangent: { bspline: pts } } } };
    expect(curveEntries(boundary).map((e) => e.ref)).toEqual(['uMin', 'uMax', 'vMin', 'vMax', 'uMinSecond', 'vMinSecond']);
    const closed = { type: 'bspline-pde', 'closed-blend': { n: 5, start: { bspline: pts }, end: { bspline: pts } } };
    expect(curveEntries(closed).map((e) => e.ref)).toEqual(['start', 'end']);
  });
});

describe('spine drags', () => {
  const u = [0, 0.5, 1];
  const points: Vec3[] = [[0, 0, 0], [0, 0, 0.5], [0, 0, 1]];
  it('add an edit holding the other handles where they are', () => {
    expect(spineWith([], u, points, 1, [1, 0, 0.5])).toEqual([{ u, moved: [[0, 0, 0], [1, 0, 0.5], [0, 0, 1]] }]);
  });
  it('change the last edit when it is on the same handles (one edit per set of handles)', () => {
    const first = spineWith([], u, points, 1, [1, 0, 0.5]);
    const second = spineWith(first, u, [[0, 0, 0], [1, 0, 0.5], [0, 0, 1]], 2, [0, 1, 1]);
    expect(second).toEqual([{ u, moved: [[0, 0, 0], [1, 0, 0.5], [0, 1, 1]] }]);
    // Other handles: a new edit after the model's own.
    expect(spineWith(second, [0, 1], [[0, 0, 0], [0, 1, 1]], 0, [2, 0, 0])).toHaveLength(2);
  });
});

describe('operator', () => {
  it('reads the files defaults: Ugail a = N, 6 modes, the remainder on; a chain a = 1', () => {
    expect(operatorOf({ type: 'spectral', operator: 'ugail', N: 4 })).toEqual({ operator: 'ugail', N: 4, a: 4, modes: 6, remainder: true });
    expect(operatorOf({ type: 'cross-sections', modes: 3 })).toEqual({ operator: null, N: null, a: 1, modes: 3, remainder: true });
  });
});
