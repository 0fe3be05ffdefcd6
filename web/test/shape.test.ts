// The shape editor's edits (shape.ts): the edit a drag of one of the server's handles sends
// (absolute, so a drag's later steps replace its earlier ones), and the panels the server's
// settings show.
import { describe, expect, it } from 'vitest';
import type { ShapeSettings, Vec3 } from '../src/api';
import { CLOSED_CURVE_FALLOFF, curveMoveEdit, dragEdit, shapePanels } from '../src/shape';
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
    expect(dragEdit(point, [2, 0, 0], handles)).toEqual({ op: 'move-curve-points', curve: 0, points: [3], positions: [[2, 0, 0]], falloff: CLOSED_CURVE_FALLOFF });
    const named: Handle = { kind: 'curve', curve: 'uMin', point: 1, p: [1, 0, 0] };
    expect(dragEdit(named, [2, 0, 0], handles)).toEqual({ op: 'move-curve-points', curve: 'uMin', points: [1], positions: [[2, 0, 0]] });
  });

  it('of a tangent tip sets its vector (tip - base) / tangentDraw; of a mean tip, a0', () => {
    expect(dragEdit(tip, [tip.base[0], tip.base[1], tip.base[2] + 0.5], handles)).toEqual({
      op: 'move-curve-points',
      curve: 1,
      points: [2],
      positions: [[0, 0, 0.5 / handles.tangentDraw]],
    });
    expect(dragEdit(mean, [1, 0, 1.5], handles)).toEqual({ op: 'set-fourier', curve: 3, a0: [1 / handles.tangentDraw, 0, 0.5 / handles.tangentDraw] });
  });

  it('of a control point moves it', () => {
    const control: Handle = { kind: 'control', i: 1, j: 2, p: [1, 2, 0] };
    expect(dragEdit(control, [9, 9, 9], handles)).toEqual({ op: 'move-control-points', points: [[1, 2]], positions: [[9, 9, 9]] });
  });

  it('of a spine point names the point and where it goes (the server holds the others)', () => {
    expect(dragEdit(spine[1], [1, 0, 0.5], handles)).toEqual({ op: 'move-spine-point', index: 1, position: [1, 0, 0.5] });
  });

  it('a whole curve moves by a translation from the drag\'s start (absolute steps)', () => {
    expect(curveMoveEdit('uMin', [0, 0, 0.25])).toEqual({ op: 'transform-curve', curve: 'uMin', translate: [0, 0, 0.25], from: 'group-start' });
  });
});

describe('panels from the server\'s settings (GET /api/model\'s "settings")', () => {
  const curveOps = ['move-curve-points', 'transform-curve', 'set-fourier'];
  it('a spectral model: its operator with kind and N; no sections, no chain', () => {
    const operator = { operator: 'fu', N: 3, a: 1.5, modes: 4, remainder: false } as const;
    const settings: ShapeSettings = { edits: [...curveOps, 'set-operator', 'set-spine', 'move-spine-point'], overlay: 'Curves and spine', operator };
    expect(shapePanels(settings)).toEqual({ sections: false, operator, operatorKind: true, operatorN: true, globalChain: false });
  });
  it('a chain: sections and its operator without kind or N; the global chain offered to a marching one', () => {
    const operator = { a: -1, modes: 6, remainder: true, method: 'c2' } as const;
    const settings: ShapeSettings = { edits: [...curveOps, 'set-operator', 'add-section', 'remove-section'], overlay: 'Curves and spine', operator };
    expect(shapePanels(settings)).toEqual({ sections: true, operator, operatorKind: false, operatorN: false, globalChain: true });
    expect(shapePanels({ ...settings, operator: { ...operator, method: 'global' } }).globalChain).toBe(false);
  });
  it('a B-spline PDE model: no operator, no sections', () => {
    const settings: ShapeSettings = { edits: [...curveOps, 'move-control-points'], overlay: 'Control nets' };
    expect(shapePanels(settings)).toEqual({ sections: false, operator: null, operatorKind: false, operatorN: false, globalChain: false });
  });
});
