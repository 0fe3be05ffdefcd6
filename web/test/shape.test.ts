// The shape editor's edits (shape.ts): the edit a drag of one of the server's handles sends
// (absolute, so a drag's later steps replace its earlier ones), and the spine list a spine
// drag makes.
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../src/api';
import { CLOSED_CURVE_FALLOFF, curveMoveEdit, dragEdit, operatorOf, spineWith } from '../src/shape';
import type { Handle, ShapeHandles } from '../src/shape';

const circle = (z: number, n = 5): Vec3[] =>
  Array.from({ length: n }, (_, j) => [Math.cos((2 * Math.PI * j) / n), Math.sin((2 * Math.PI * j) / n), z] as Vec3);

describe('drags of the server\'s handles', () => {
  // Handles as GET /api/model's "handles" lists them (SurfaceMethod::handles; where they are is
  // checked against the model files in tests/session/handles_test.cpp).
  const tip: Handle = { kind: 'tangent', curve: 1, point: 2, base: circle(0)[2], p: [0, 0, 0] };
  const mean: Handle = { kind: 'tangent', curve: 3, point: 0, base: [0, 0, 1], p: [0, 0, 1.5], mean: true };
  const spine: Handle[] = [0, 0.5, 1].map((u, index) => ({ kind: 'spine', index, u, p: [0, 0, u] as Vec3 }));
  const handles: ShapeHandles = { points: [tip, mean, ...spine], curves: [], tangentDraw: 0.25 };

  it('of a point of a closed curve moves it with a falloff; of a named curve alone', () => {
    const point: Handle = { kind: 'curve', curve: 0, point: 3, p: [1, 0, 0] };
    expect(dragEdit(point, [2, 0, 0], [], handles)).toEqual({ op: 'move-curve-points', curve: 0, points: [3], positions: [[2, 0, 0]], falloff: CLOSED_CURVE_FALLOFF });
    const named: Handle = { kind: 'curve', curve: 'uMin', point: 1, p: [1, 0, 0] };
    expect(dragEdit(named, [2, 0, 0], [], handles)).toEqual({ op: 'move-curve-points', curve: 'uMin', points: [1], positions: [[2, 0, 0]] });
  });

  it('of a tangent tip sets its vector (tip - base) / tangentDraw; of a mean tip, a0', () => {
    expect(dragEdit(tip, [tip.base[0], tip.base[1], tip.base[2] + 0.5], [], handles)).toEqual({
      op: 'move-curve-points',
      curve: 1,
      points: [2],
      positions: [[0, 0, 0.5 / handles.tangentDraw]],
    });
    expect(dragEdit(mean, [1, 0, 1.5], [], handles)).toEqual({ op: 'set-fourier', curve: 3, a0: [1 / handles.tangentDraw, 0, 0.5 / handles.tangentDraw] });
  });

  it('of a control point moves it', () => {
    const control: Handle = { kind: 'control', i: 1, j: 2, p: [1, 2, 0] };
    expect(dragEdit(control, [9, 9, 9], [], handles)).toEqual({ op: 'move-control-points', points: [[1, 2]], positions: [[9, 9, 9]] });
  });

  it('of a spine point holds the other spine handles where they are, at their u', () => {
    expect(dragEdit(spine[1], [1, 0, 0.5], [], handles)).toEqual({ op: 'set-spine', spine: [{ u: [0, 0.5, 1], moved: [[0, 0, 0], [1, 0, 0.5], [0, 0, 1]] }] });
  });

  it('a whole curve moves by a translation from the drag\'s start (absolute steps)', () => {
    expect(curveMoveEdit('uMin', [0, 0, 0.25])).toEqual({ op: 'transform-curve', curve: 'uMin', translate: [0, 0, 0.25], from: 'group-start' });
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
