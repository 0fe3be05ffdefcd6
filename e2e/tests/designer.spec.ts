// What a designer new to the studio met (issue 27), each as a regression test: quick
// transforms pressed faster than the page reloads, a view preset right after an orbit, two
// vertices at one place picked by clicking, a weld refused in the designer's words, a split
// that leaves no vertex unused, and a point drag of a marching chain told about before it is
// made and turned into the global chain; and the designer tools, each checked in the saved
// file: selections and typed moves, axis lock and snap, drags in the shaded view, Delete on the
// selection, Split on several frames or all, symmetric drags and Mirror, drags snapped to
// vertices, frame edges and the surface, a distance typed during a drag; and Ctrl+A pressed
// while an undo reloads.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { clickPatch, expect, newModel, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** A coordinate the studio computes from typed numbers (a quarter turn, a scale) is exact to
 * rounding. */
const ROUNDING = 1e-9;
/** A preset's camera looks along its axis to rounding (no damping left over from an orbit). */
const ON_AXIS = 1e-9;
/** The top view's camera leans this far toward -y (VIEW_DIRECTIONS in web/src/viewport.ts): a
 * drag in the plane facing it rises by at most this fraction of its length. */
const TOP_VIEW_TILT = 1e-4;
/** The effect arrow is the panel's formula applied to the file's numbers (rounding only). */
const ARROW_ROUNDING = 1e-9;
/** The surface under a force moves by the formula's amount at the region's middle (the
 * particular solution is added to the rest): the arrow's tail (the tip, on the surface, less
 * the formula) stays put as f0 changes, to rounding (a fraction of the move). */
const FORCE_EFFECT_MATCH = 1e-9;

type Point = { x: number; y: number };
const hook = <T>(page: Page, name: string, ...args: unknown[]) =>
  page.evaluate(([n, a]) => (window as any).__studio[n as string](...(a as unknown[])), [name, args] as const) as Promise<T>;
const model = async (studio: Studio) => (await studio.state()).model;
const selected = async (page: Page) => (await hook<{ vertices: number[] }>(page, 'selection')).vertices;

/** Selects every vertex of a model with a box round the whole frame view. */
async function selectAll(page: Page): Promise<void> {
  const box = (await page.getByTestId('frame-view').boundingBox())!;
  await page.keyboard.down('Shift');
  await page.mouse.move(box.x + 4, box.y + 40);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width - 4, box.y + box.height - 4, { steps: 4 });
  await page.mouse.up();
  await page.keyboard.up('Shift');
}

/** (x, y) turned about z by `degrees` round (cx, cy). */
function turned(p: number[], c: number[], degrees: number): number[] {
  const a = (degrees * Math.PI) / 180;
  const [dx, dy] = [p[0] - c[0], p[1] - c[1]];
  return [c[0] + Math.cos(a) * dx - Math.sin(a) * dy, c[1] + Math.sin(a) * dx + Math.cos(a) * dy, p[2]];
}

const close = (a: number[], b: number[]) => a.every((x, i) => Math.abs(x - b[i]) < ROUNDING);

test.describe.configure({ timeout: 180_000 });

test('quick transforms each start from the one before: two turns, a turn then a scale, an undo then a turn', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'quick.json', 2, 1);
  const m = await model(studio);
  const centre = [0, 1, 2].map((c) => {
    const xs = m.vertices.map((p: number[]) => p[c]);
    return (Math.min(...xs) + Math.max(...xs)) / 2;
  });
  await page.getByTestId('view-top').click();
  await selectAll(page);
  await expect.poll(async () => (await selected(page)).length).toBe(m.vertices.length);
  await page.getByTestId('selection-degrees').fill('90');
  await page.locator('body').click({ position: { x: 5, y: 5 } }); // keys are keys again

  // Shift+R twice at once (key repeat): two quarter turns, two undo steps.
  await page.keyboard.press('Shift+R');
  await page.keyboard.press('Shift+R');
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  await settle(page);
  let now = await model(studio);
  m.vertices.forEach((p: number[], v: number) => expect(close(now.vertices[v], turned(p, centre, 180))).toBe(true));

  // Shift+R then Shift+S at once: the scale acts on the turned vertices.
  await page.getByTestId('selection-scale').fill('2');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  const before = now.vertices;
  await page.keyboard.press('Shift+R');
  await page.keyboard.press('Shift+S');
  await expect.poll(async () => (await studio.state()).undo).toBe(4);
  await settle(page);
  now = await model(studio);
  before.forEach((p: number[], v: number) => {
    const t = turned(p, centre, 90);
    expect(close(now.vertices[v], [0, 1, 2].map((c) => centre[c] + 2 * (t[c] - centre[c])))).toBe(true);
  });

  // Ctrl+Z then Shift+R at once: the turn acts on the vertices as the undo left them (two
  // changes: the undo's and the turn's revision).
  const revision = (await studio.state()).revision;
  await page.keyboard.press('Control+z');
  await page.keyboard.press('Shift+R');
  await expect.poll(async () => (await studio.state()).revision).toBe(revision + 2);
  expect((await studio.state()).undo).toBe(4);
  await settle(page);
  now = await model(studio);
  before.forEach((p: number[], v: number) => expect(close(now.vertices[v], turned(p, centre, 180))).toBe(true));
});

test('a view preset right after an orbit looks exactly along its axis', async ({ page, studio }) => {
  await openStudio(page, studio);
  const box = (await page.getByTestId('surface-view').boundingBox())!;
  const at = { x: box.x + box.width / 2, y: box.y + box.height / 2 };
  for (const [key, direction] of [
    ['1', [0, -1, 0]],
    ['3', [1, 0, 0]],
  ] as const) {
    // A quick orbit, released while still turning; the preset's key at once.
    await page.mouse.move(at.x, at.y);
    await page.mouse.down();
    await page.mouse.move(at.x + 160, at.y + 40, { steps: 3 });
    await page.mouse.up();
    await page.keyboard.press(key);
    await page.waitForTimeout(500); // damping would have turned the camera by now
    const cameras = await hook<Record<string, { direction: number[] }>>(page, 'cameras');
    for (const view of ['frame', 'surface'])
      cameras[view].direction.forEach((x, i) => expect(Math.abs(x - direction[i])).toBeLessThan(ON_AXIS));
  }
});

test('two vertices at one place are both picked by shift+clicks; a weld the frames cannot take is refused in plain words', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'weld.json', 3, 1);
  // Two frames apart (the middle one deleted), the second's corner P1 moved onto the first's
  // P3: two vertices at one place, on no one frame.
  expect(await hook<string>(page, 'edit', { op: 'delete-frames', frames: [1] })).toBe('');
  let m = await model(studio);
  const a = m.frames[0].vertices[2];
  const b = m.frames[1].vertices[0];
  expect(await hook<string>(page, 'edit', { op: 'move-vertex', vertex: b, position: m.vertices[a] })).toBe('');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(400);
  const p = await hook<Point>(page, 'vertexScreen', a);
  await page.keyboard.down('Shift');
  await page.mouse.click(p.x, p.y);
  await page.mouse.click(p.x, p.y);
  await page.keyboard.up('Shift');
  await expect.poll(async () => [...(await selected(page))].sort((x, y) => x - y)).toEqual([a, b].sort((x, y) => x - y));
  await page.screenshot({ path: shot('designer-coincident.png') });
  await page.keyboard.press('w');
  await expect.poll(async () => (await model(studio)).vertices.length).toBe(m.vertices.length - 1);

  // The frames' other corners of the sides that now touch welded too: the sides would share
  // their ends but not their middles. Refused, said with frames and vertices.
  m = await model(studio);
  const c = m.frames[0].vertices[4];
  const d = m.frames[1].vertices[6];
  await page.waitForTimeout(300);
  const pc = await hook<Point>(page, 'vertexScreen', c);
  const pd = await hook<Point>(page, 'vertexScreen', d);
  await page.mouse.click(pc.x, pc.y);
  await page.keyboard.down('Shift');
  await page.mouse.click(pd.x, pd.y);
  await page.keyboard.up('Shift');
  await expect.poll(async () => selected(page)).toEqual([c, d]);
  await page.keyboard.press('w');
  const error = page.getByTestId('error');
  await expect(error).toContainText('would meet at the two ends of a side');
  const text = (await error.textContent()) ?? '';
  expect(text).not.toContain('$.');
  expect(text).not.toMatch(/P\d-P\d-P\d/);
  expect((await model(studio)).vertices.length).toBe(m.vertices.length);
});

test('a split adds no vertex that no frame uses', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'split.json');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await expect(async () => {
    const q = await hook<Point>(page, 'patchScreen', 0);
    await page.mouse.click(q.x, q.y);
    expect((await hook<{ frames: number[] }>(page, 'selection')).frames).toEqual([0]);
  }).toPass({ timeout: 30000 });
  await page.keyboard.press('s');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(4);
  const m = await model(studio);
  const used = new Set<number>(m.frames.flatMap((f: { vertices: number[] }) => f.vertices));
  expect(m.vertices.length).toBe(21);
  expect(used.size).toBe(m.vertices.length);
});

test.describe('a marching chain', () => {
  test.use({ example: 'vase-sections.json' });
  test('is told about before a drag, and the global chain is one click', async ({ page, studio }) => {
    await openStudio(page, studio);
    // The example is global: made a marching chain through the API, the page warns.
    expect(await hook<string>(page, 'edit', { op: 'set-operator', method: 'c2' })).toBe('');
    await page.reload();
    await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
    await expect(page.getByTestId('drag-advice')).toBeVisible();
    await expect(page.getByTestId('drag-advice-text')).toContainText('marching method "c2"');
    await page.screenshot({ path: shot('designer-drag-advice.png') });
    await page.getByTestId('use-global-chain').click();
    await expect(page.getByTestId('drag-advice')).toBeHidden();
    expect((await model(studio)).method).toBe('global');
  });
});

/** Opens the studio on a new row of 3 frames (New…) less its middle one: two islands, x from
 * 0 to 1 and from 2 to 3, seen from the top; their model. */
async function twoIslands(page: Page, studio: Studio, file: string) {
  await openStudio(page, studio);
  await newModel(page, 'grid', file, 3, 1);
  expect(await hook<string>(page, 'edit', { op: 'delete-frames', frames: [1] })).toBe('');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(400);
  return model(studio);
}

test('select linked, invert, all, with moves typed as expressions: the saved file has the numbers', async ({ page, studio }) => {
  // Two islands: frame 0, and the old frame 2 (the middle one deleted).
  const m = await twoIslands(page, studio, 'islands.json');
  const island0 = [...new Set<number>(m.frames[0].vertices)];
  const island1 = [...new Set<number>(m.frames[1].vertices)];
  const p = await hook<Point>(page, 'vertexScreen', m.frames[0].vertices[1]);
  await page.mouse.click(p.x, p.y);
  await page.keyboard.press('Control+l');
  await expect.poll(async () => [...(await selected(page))].sort((a, b) => a - b)).toEqual(island0.sort((a, b) => a - b));

  // The linked island moved by dz = 2*pi/10, typed as such.
  const moveBy = async (axis: string, text: string) => {
    for (const a of ['x', 'y', 'z']) await page.getByTestId(`offset-${a}`).fill(a === axis ? text : '0');
    await page.getByTestId('offset-apply').click();
    await settle(page);
  };
  await moveBy('z', '2*pi/10');
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  // Inverted: the other island, moved by dx = 1/3.
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('Control+i');
  await expect.poll(async () => [...(await selected(page))].sort((a, b) => a - b)).toEqual(island1.sort((a, b) => a - b));
  await moveBy('x', '1/3');
  await expect.poll(async () => (await studio.state()).undo).toBe(3);
  // All: every vertex moved by dy = -sqrt(2)/2.
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('Control+a');
  await expect.poll(async () => (await selected(page)).length).toBe(m.vertices.length);
  await moveBy('y', '-sqrt(2)/2');
  await expect.poll(async () => (await studio.state()).undo).toBe(4);
  await page.screenshot({ path: shot('designer-select.png') });

  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  const saved = JSON.parse(readFileSync(path.join(studio.root, 'islands.json'), 'utf8'));
  m.vertices.forEach((q: number[], v: number) => {
    const expected = [
      q[0] + (island1.includes(v) ? 1 / 3 : 0),
      q[1] - Math.sqrt(2) / 2,
      q[2] + (island0.includes(v) ? (2 * Math.PI) / 10 : 0),
    ];
    expect(close(saved.vertices[v], expected)).toBe(true);
  });
});

test('X during a drag locks it to x, and a snap step rounds the move: the saved file has it', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'snap.json');
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(400);
  await page.getByTestId('snap-step').fill('1/8');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  const m = await model(studio);
  const v = m.frames[0].vertices[4]; // P5, the corner (1, 1, 0)
  const p = await hook<Point>(page, 'vertexScreen', v);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(p.x + 30, p.y - 40, { steps: 3 });
  await page.keyboard.press('x'); // the drag's axis lock, not Delete frames
  await page.mouse.move(p.x + 90, p.y - 60, { steps: 4 });
  await page.mouse.up();
  await settle(page);
  await page.screenshot({ path: shot('designer-axis-snap.png') });
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  const saved = JSON.parse(readFileSync(path.join(studio.root, 'snap.json'), 'utf8'));
  expect(saved.frames).toHaveLength(1);
  const [x, y, z] = saved.vertices[v];
  const dx = x - m.vertices[v][0];
  expect(dx).toBeGreaterThan(0.1);
  expect(Math.abs(dx * 8 - Math.round(dx * 8))).toBeLessThan(ROUNDING); // steps of 1/8
  expect(y).toBe(m.vertices[v][1]);
  expect(z).toBe(m.vertices[v][2]);
  expect((await studio.state()).undo).toBe(1);
});

test('a vertex dragged in the shaded surface view moves as its handle would: one undo step', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'shaded.json');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(400);
  const m = await model(studio);
  const v = m.frames[0].vertices[4];
  const p = await hook<Point & { visible: boolean }>(page, 'vertexSurfaceScreen', v);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(p.x + 60, p.y, { steps: 6 }); // top view: screen right is +x
  await page.mouse.up();
  await settle(page);
  await page.screenshot({ path: shot('designer-surface-drag.png') });
  const now = (await model(studio)).vertices[v];
  expect(now[0] - m.vertices[v][0]).toBeGreaterThan(0.05);
  expect(Math.abs(now[1] - m.vertices[v][1])).toBeLessThan(0.02);
  expect(Math.abs(now[2] - m.vertices[v][2])).toBeLessThan(0.02);
  expect((await studio.state()).undo).toBe(1);
  // The camera did not orbit: still the top view.
  const cameras = await hook<Record<string, { direction: number[] }>>(page, 'cameras');
  expect(cameras.surface.direction[2]).toBeGreaterThan(0.999);
});

/** Opens the studio on a new model (New…) seen from `view` (the top by default). */
async function newModelInView(page: Page, studio: Studio, kind: string, file: string, u = 1, v = 1, view = 'top'): Promise<void> {
  await openStudio(page, studio);
  await newModel(page, kind, file, u, v);
  await page.getByTestId(`view-${view}`).click();
  await page.waitForTimeout(400);
}

/** The saved file of `name` in the studio's root, after Ctrl+S. */
async function saved(page: Page, studio: Studio, name: string) {
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  return JSON.parse(readFileSync(path.join(studio.root, name), 'utf8'));
}

test('Delete deletes the selected frames in one undo step; Shift+Delete removes a force instead', async ({ page, studio }) => {
  await newModelInView(page, studio, 'grid', 'delete.json', 3, 1);
  const m = await model(studio);
  await clickPatch(page, 0);
  await clickPatch(page, 2, true);
  expect((await hook<{ frames: number[] }>(page, 'selection')).frames.sort()).toEqual([0, 2]);
  // Shift+Delete with no force selected removes nothing (a frame's forces, not frames).
  await page.keyboard.press('Shift+Delete');
  await expect(page.getByTestId('status')).toContainText('select a frame and one of its forces');
  expect((await model(studio)).frames).toHaveLength(3);
  await page.keyboard.press('Delete');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(1);
  expect((await studio.state()).undo).toBe(1);
  const file = await saved(page, studio, 'delete.json');
  // What is left is the old middle frame, its 8 vertices where they were, in its order.
  expect(file.frames).toHaveLength(1);
  expect(file.vertices).toHaveLength(8);
  const kept = m.frames[1].vertices.map((v: number) => m.vertices[v]);
  expect(file.frames[0].vertices.map((v: number) => file.vertices[v])).toEqual(kept);
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(3);
});

/** Every vertex of a saved file is used by a frame, and all of them lie on the flat grid's
 * lattice of `step` (a split places new vertices on the surface: the plane z = 0). */
function onLattice(file: { vertices: number[][]; frames: { vertices: number[] }[] }, step: number): void {
  const used = new Set(file.frames.flatMap((f) => f.vertices));
  expect(used.size).toBe(file.vertices.length);
  for (const p of file.vertices) {
    for (const c of [0, 1]) expect(Math.abs(p[c] / step - Math.round(p[c] / step))).toBeLessThan(ROUNDING);
    expect(Math.abs(p[2])).toBeLessThan(ROUNDING);
  }
}

test('Split 4 on several frames, then on all: shared edges stay shared, no vertex unused, one undo step each', async ({ page, studio }) => {
  await newModelInView(page, studio, 'grid', 'subdivide.json', 3, 1);
  // Frames 0 and 2 into 2 × 2: the cut across v runs on through frame 1, which becomes 2.
  await clickPatch(page, 0);
  await clickPatch(page, 2, true);
  await page.keyboard.press('s');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(4 + 2 + 4);
  expect((await studio.state()).undo).toBe(1);
  await page.screenshot({ path: shot('designer-split-several.png') });
  // 11 columns × 5 rows of lattice points less the 10 frames' centres.
  let file = await saved(page, studio, 'subdivide.json');
  expect(file.vertices).toHaveLength(11 * 5 - 10);
  onLattice(file, 0.25);
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(3);
  // The page holds the undone model before Ctrl+A selects its frames (else Ctrl+A selects the
  // 10 frames of the split model, and the undo's reload then clears that selection).
  await settle(page);
  const undone = (await studio.state()).revision;
  await expect.poll(async () => (await hook<{ revision: number }>(page, 'state')).revision).toBe(undone);

  // Ctrl+A, S: every frame into 2 × 2, a 6 × 2 grid of frames (13 × 5 points less 12 centres).
  await page.keyboard.press('Control+a');
  await page.keyboard.press('s');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(12);
  expect((await studio.state()).undo).toBe(1);
  await page.screenshot({ path: shot('designer-subdivide-all.png') });
  file = await saved(page, studio, 'subdivide.json');
  expect(file.vertices).toHaveLength(13 * 5 - 12);
  onLattice(file, 0.25);
});

test('symmetry across x = 0: a drag moves the mirror partner mirrored and keeps a vertex on the plane on it', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'mirror.json', 2, 1);
  // Centred on x = 0: x from -1 to 1.
  const m0 = await model(studio);
  const centred = m0.vertices.map((p: number[]) => [p[0] - 1, p[1], p[2]]);
  expect(await hook<string>(page, 'edit', { op: 'move-vertices', vertices: centred.map((_: unknown, v: number) => v), positions: centred })).toBe('');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('symmetry').selectOption('x');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(400);
  const find = (x: number, y: number) => centred.findIndex((p: number[]) => Math.abs(p[0] - x) < ROUNDING && Math.abs(p[1] - y) < ROUNDING);
  const corner = find(-1, 0), partner = find(1, 0), middle = find(0, 1);
  const drag = async (v: number, dx: number, dy: number) => {
    const p = await hook<Point>(page, 'vertexScreen', v);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    await page.mouse.move(p.x + dx, p.y + dy, { steps: 4 });
    await page.mouse.up();
    await settle(page);
  };
  await drag(corner, 30, 20); // top view: screen right is +x, down is -y
  await drag(middle, 25, -25);
  await page.screenshot({ path: shot('designer-symmetry.png') });
  const file = await saved(page, studio, 'mirror.json');
  const c = file.vertices[corner], q = file.vertices[partner], mid = file.vertices[middle];
  expect(c[0] - centred[corner][0]).toBeGreaterThan(0.05);
  expect(c[1] - centred[corner][1]).toBeLessThan(-0.05);
  // The partner is the corner mirrored: -x, the same y and z.
  expect(Math.abs(q[0] + c[0])).toBeLessThan(ROUNDING);
  expect(Math.abs(q[1] - c[1])).toBeLessThan(ROUNDING);
  expect(Math.abs(q[2] - c[2])).toBeLessThan(ROUNDING);
  // The middle stayed on the plane; it moved along it.
  expect(mid[0]).toBe(0);
  expect(mid[1] - 1).toBeGreaterThan(0.05);
  // Everything else where it was; one undo step per drag (after the centring).
  file.vertices.forEach((p: number[], v: number) => {
    if (![corner, partner, middle].includes(v)) expect(p).toEqual(centred[v]);
  });
  expect((await studio.state()).undo).toBe(3);
});

test('Mirror copies the selected frame across x = 0, welded at the seam: the saved file has the mirror image', async ({ page, studio }) => {
  await newModelInView(page, studio, 'single', 'mirror-frames.json');
  const m = await model(studio);
  await clickPatch(page, 0);
  // Without a plane chosen, Mirror says what to do and changes nothing.
  await page.keyboard.press('m');
  await expect(page.getByTestId('error')).toContainText('choose the symmetry plane');
  await page.getByTestId('symmetry').selectOption('x');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await clickPatch(page, 0);
  await page.keyboard.press('m');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(2);
  expect((await studio.state()).undo).toBe(1);
  await page.keyboard.press('Shift+F');
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('designer-mirror.png') });
  const file = await saved(page, studio, 'mirror-frames.json');
  // The 3 vertices on x = 0 are shared; the 5 others copied at -x.
  expect(file.vertices).toHaveLength(8 + 5);
  expect(file.vertices.slice(0, 8)).toEqual(m.vertices);
  for (const p of file.vertices.slice(8)) {
    expect(p[0]).toBeLessThan(0);
    expect(m.vertices.some((q: number[]) => q[0] === -p[0] && q[1] === p[1] && q[2] === p[2])).toBe(true);
  }
  // The two frames share one side: the seam's three vertices.
  const [a, b] = file.frames.map((f: { vertices: number[] }) => new Set(f.vertices));
  expect([...a].filter((v) => b.has(v)).sort()).toEqual(m.vertices.flatMap((q: number[], v: number) => (q[0] === 0 ? [v] : [])).sort());
});

test('Ctrl+A pressed while an undo is reloading selects the frames of the model the undo restores', async ({ page, studio }) => {
  await newModelInView(page, studio, 'grid', 'race.json', 3, 1);
  await page.keyboard.press('Control+a');
  await page.keyboard.press('s');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(12);
  await settle(page);
  // The undo answered late (a loaded machine): Ctrl+A comes while it is in flight. It waits
  // for the undo's reload, as the toolbar's actions do, and selects the 3 frames it restores
  // (before, it selected the 12 frames of the split model, which the reload then cleared).
  await page.route('**/api/undo', async (route) => {
    await new Promise((r) => setTimeout(r, 600));
    await route.continue();
  });
  await page.keyboard.press('Control+z');
  await page.keyboard.press('Control+a');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(3);
  await expect.poll(async () => [...(await hook<{ frames: number[] }>(page, 'selection')).frames].sort()).toEqual([0, 1, 2]);
  await page.keyboard.press('s');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(12);
  expect((await studio.state()).undo).toBe(1);
});

/** Presses vertex `v`'s handle in the frame view, moves the pointer to `to` (client pixels)
 * in steps, and releases it; the page's edits answered. */
async function dragHandleTo(page: Page, v: number, to: Point): Promise<void> {
  const p = await hook<Point>(page, 'vertexScreen', v);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps: 6 });
  await page.mouse.up();
  await settle(page);
}

/** The client point a fraction `t` of the way from a to b. */
const between = (a: Point, b: Point, t: number): Point => ({ x: a.x + t * (b.x - a.x), y: a.y + t * (b.y - a.y) });

test('snapping drags to a vertex and to a frame edge: the saved file has the vertex exactly there', async ({ page, studio }) => {
  const m = await twoIslands(page, studio, 'snap-to.json');
  const [left, right] = m.frames.map((f: { vertices: number[] }) => f.vertices);

  // Vertices: the right frame's P1 dropped a few pixels off the left frame's P3 lands on it.
  await page.getByTestId('snap-to').selectOption('vertices');
  const target = await hook<Point>(page, 'vertexScreen', left[2]);
  await dragHandleTo(page, right[0], { x: target.x + 4, y: target.y - 3 });
  // Frame edges: its P7 dropped 4 px right of the left frame's side x = 1 (between P4 and P5)
  // lands on that side.
  await page.getByTestId('snap-to').selectOption('edges');
  const side = between(await hook<Point>(page, 'vertexScreen', left[3]), await hook<Point>(page, 'vertexScreen', left[4]), 0.4);
  await dragHandleTo(page, right[6], { x: side.x + 4, y: side.y });
  await page.screenshot({ path: shot('designer-snap-edge.png') });

  const file = await saved(page, studio, 'snap-to.json');
  expect(file.vertices[right[0]]).toEqual(m.vertices[left[2]]);
  const [x, y, z] = file.vertices[right[6]];
  expect(Math.abs(x - 1)).toBeLessThan(ROUNDING);
  expect(y).toBeGreaterThan(0.5);
  expect(y).toBeLessThan(1);
  expect(Math.abs(z)).toBeLessThan(ROUNDING);
  // Nothing else moved; one undo step per drag (after the delete).
  file.vertices.forEach((p: number[], v: number) => {
    if (v !== right[0] && v !== right[6]) expect(p).toEqual(m.vertices[v]);
  });
  expect((await studio.state()).undo).toBe(3);
});

test('snapping a drag onto the surface: the vertex lands on the patch under the pointer, not in the plane facing the camera', async ({ page, studio }) => {
  await newModelInView(page, studio, 'grid', 'snap-surface.json', 2, 1, 'iso');
  const m = await model(studio);
  const [left, right] = m.frames.map((f: { vertices: number[] }) => f.vertices);
  await page.getByTestId('snap-to').selectOption('surface');
  // The right frame's far corner dropped on the middle of the left frame's diagonal (P1 to P5,
  // on the plane z = 0).
  const to = between(await hook<Point>(page, 'vertexScreen', left[0]), await hook<Point>(page, 'vertexScreen', left[4]), 0.5);
  await dragHandleTo(page, right[4], to);
  await page.screenshot({ path: shot('designer-snap-surface.png') });
  const file = await saved(page, studio, 'snap-surface.json');
  const [x, y, z] = file.vertices[right[4]];
  expect(Math.abs(z)).toBeLessThan(ROUNDING); // on the surface z = 0
  expect(x).toBeGreaterThan(0.2);
  expect(x).toBeLessThan(0.8);
  expect(Math.abs(x - y)).toBeLessThan(0.05); // on the diagonal, to a pixel or so
  expect((await studio.state()).undo).toBe(1);
});

test('X with snapping to frame edges, then onto the surface: the vertex slides along x to the target\'s x, its y and z kept', async ({ page, studio }) => {
  const m = await twoIslands(page, studio, 'lock-snap.json'); // x from 0 to 1 and from 2 to 3
  const at = (p: number[]) => m.vertices.findIndex((q: number[]) => close(q, p));
  const moved = at([2, 0.5, 0]); // the right island's left side's middle
  const lockedDrag = async (to: Point) => {
    const p = await hook<Point>(page, 'vertexScreen', moved);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    await page.mouse.move((p.x + to.x) / 2, (p.y + to.y) / 2, { steps: 3 });
    await page.keyboard.press('x');
    await page.mouse.move(to.x, to.y, { steps: 5 });
    await page.mouse.up();
    await settle(page);
  };
  // Frame edges: released 4 px right of the left island's side x = 1, a fifth of the way up it
  // (y about 0.2): the target there is on that side, so x = 1; y = 0.5 and z = 0 kept.
  await page.getByTestId('snap-to').selectOption('edges');
  const side = between(await hook<Point>(page, 'vertexScreen', at([1, 0, 0])), await hook<Point>(page, 'vertexScreen', at([1, 0.5, 0])), 0.4);
  await lockedDrag({ x: side.x + 4, y: side.y });
  let file = await saved(page, studio, 'lock-snap.json');
  expect(file.vertices[moved]).toEqual([1, 0.5, 0]);
  file.vertices.forEach((p: number[], v: number) => v === moved || expect(p).toEqual(m.vertices[v]));
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await studio.state()).undo).toBe(1); // the delete of twoIslands
  await settle(page);

  // The surface, seen at three quarters (where a plain X lock would land elsewhere): released
  // over the left island's patch near (0.5, 0.25, 0); x becomes that of the surface's point
  // under the pointer (the surface as the drag began: the page's own hit test of that point).
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(400);
  await page.getByTestId('snap-to').selectOption('surface');
  const over = between(await hook<Point>(page, 'vertexScreen', at([0.5, 0, 0])), await hook<Point>(page, 'vertexScreen', at([0.5, 1, 0])), 0.25);
  const to = { x: Math.round(over.x), y: Math.round(over.y) };
  const target = (await hook<number[] | null>(page, 'surfaceUnder', to.x, to.y))!;
  expect(Math.abs(target[1] - 0.5)).toBeGreaterThan(0.1); // off the axis: the lock matters
  await lockedDrag(to);
  await page.screenshot({ path: shot('designer-lock-snap-surface.png') });
  file = await saved(page, studio, 'lock-snap.json');
  const [x, y, z] = file.vertices[moved];
  expect(Math.abs(x - target[0])).toBeLessThan(ROUNDING);
  expect(x).toBeGreaterThan(0.2);
  expect(x).toBeLessThan(0.8);
  expect([y, z]).toEqual([0.5, 0]);
  expect((await studio.state()).undo).toBe(2);
});

test('a distance typed during a drag moves exactly that far: along a locked axis, or along the drag; Enter applies', async ({ page, studio }) => {
  await newModelInView(page, studio, 'single', 'typed.json');
  const m = await model(studio);
  const v = m.frames[0].vertices[4]; // P5, the corner (1, 1, 0)
  const typedDrag = async (dx: number, dy: number, keys: string[]) => {
    const p = await hook<Point>(page, 'vertexScreen', v);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    await page.mouse.move(p.x + dx, p.y + dy, { steps: 4 });
    for (const k of keys) await page.keyboard.press(k);
    await page.mouse.move(p.x + 2 * dx, p.y, { steps: 3 }); // after Enter: no effect
    await page.mouse.up();
    await settle(page);
  };
  // Along x (X locks it), -3/8 typed: x - 0.375 exactly.
  await typedDrag(-40, 5, ['x', '-', '3', '/', '8', 'Enter']);
  await expect(page.getByTestId('status')).toContainText('drag: distance -3/8');
  await page.screenshot({ path: shot('designer-typed-distance.png') });
  let file = await saved(page, studio, 'typed.json');
  expect(file.vertices[v]).toEqual([0.625, 1, 0]);
  // Free, up and to the left on screen (top view: -x, +y), 0.55 typed then one digit taken
  // back: 0.5 along the drag's direction.
  await typedDrag(-30, -30, ['0', '.', '5', '5', 'Backspace', 'Enter']);
  file = await saved(page, studio, 'typed.json');
  const d = file.vertices[v].map((c: number, i: number) => c - [0.625, 1, 0][i]);
  expect(Math.abs(Math.hypot(d[0], d[1], d[2]) - 0.5)).toBeLessThan(ROUNDING);
  expect(d[0]).toBeLessThan(-0.2);
  expect(d[1]).toBeGreaterThan(0.2);
  // The top view leans 1e-4 toward -y (viewport.ts), so its facing plane climbs that much.
  expect(Math.abs(d[2])).toBeLessThan(TOP_VIEW_TILT * 0.5);
  expect((await studio.state()).undo).toBe(2);
});

test('loop and ring select (Alt+L, Alt+R) take the row and the column of frames through the picked one: moves typed on them land in the saved file', async ({ page, studio }) => {
  await newModelInView(page, studio, 'tube', 'strips.json', 4, 3, 'front');
  const m = await model(studio);
  const used = (frames: number[]) => new Set<number>(frames.flatMap((f) => m.frames[f].vertices));
  const moveBy = async (d: string[]) => {
    for (const [i, a] of ['x', 'y', 'z'].entries()) await page.getByTestId(`offset-${a}`).fill(d[i]);
    await page.getByTestId('offset-apply').click();
    await settle(page);
    await page.locator('body').click({ position: { x: 5, y: 5 } }); // keys are keys again
  };
  // Frame 6: the middle row's frame facing the camera. Its loop: the middle row round the tube.
  await clickPatch(page, 6);
  await page.keyboard.press('Alt+l');
  await expect.poll(async () => (await hook<{ frames: number[] }>(page, 'selection')).frames).toEqual([4, 5, 6, 7]);
  await moveBy(['0', '0', '1/2']);
  await page.keyboard.press('Escape');
  // Its ring: the column of frames up the tube.
  await clickPatch(page, 6);
  await page.keyboard.press('Alt+r');
  await expect.poll(async () => (await hook<{ frames: number[] }>(page, 'selection')).frames).toEqual([2, 6, 10]);
  await moveBy(['1/4', '0', '0']);
  await page.screenshot({ path: shot('designer-loop-ring.png') });
  const file = await saved(page, studio, 'strips.json');
  const loop = used([4, 5, 6, 7]), ring = used([2, 6, 10]);
  m.vertices.forEach((p: number[], v: number) => {
    const expected = [p[0] + (ring.has(v) ? 0.25 : 0), p[1], p[2] + (loop.has(v) ? 0.5 : 0)];
    expect(close(file.vertices[v], expected)).toBe(true);
  });
  expect((await studio.state()).undo).toBe(2);
});

test('symmetry through the model\'s centre: a drag and a typed move of the selection each move the partner mirrored across it', async ({ page, studio }) => {
  await newModelInView(page, studio, 'grid', 'centre-mirror.json', 2, 1);
  // x from 0 to 2: the centre plane is x = 1 (not the origin's x = 0).
  const m = await model(studio);
  await page.getByTestId('symmetry').selectOption('cx');
  const find = (x: number, y: number) => m.vertices.findIndex((p: number[]) => Math.abs(p[0] - x) < ROUNDING && Math.abs(p[1] - y) < ROUNDING);
  const [corner, partner, top, topPartner] = [find(0, 0), find(2, 0), find(0, 1), find(2, 1)];
  // The corner (0, 0) dragged: its partner (2, 0) follows mirrored across x = 1.
  const p = await hook<Point>(page, 'vertexScreen', corner);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(p.x + 25, p.y + 20, { steps: 4 });
  await page.mouse.up();
  await settle(page);
  // The corner (0, 1) picked and moved by dx = 1/4 in the panel: its partner by -1/4.
  const q = await hook<Point>(page, 'vertexScreen', top);
  await page.mouse.click(q.x, q.y);
  for (const [a, d] of [['x', '1/4'], ['y', '0'], ['z', '0']]) await page.getByTestId(`offset-${a}`).fill(d);
  await page.getByTestId('offset-apply').click();
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  await page.screenshot({ path: shot('designer-symmetry-centre.png') });
  const file = await saved(page, studio, 'centre-mirror.json');
  const c = file.vertices[corner], cp = file.vertices[partner];
  expect(c[0]).toBeGreaterThan(0.05);
  expect(Math.abs(cp[0] - (2 - c[0]))).toBeLessThan(ROUNDING);
  expect(Math.abs(cp[1] - c[1])).toBeLessThan(ROUNDING);
  expect(Math.abs(cp[2] - c[2])).toBeLessThan(ROUNDING);
  expect(close(file.vertices[top], [0.25, 1, 0])).toBe(true);
  expect(close(file.vertices[topPartner], [1.75, 1, 0])).toBe(true);
  // The middle column stays on the plane x = 1; the rest where it was.
  file.vertices.forEach((r: number[], v: number) => {
    if (![corner, partner, top, topPartner].includes(v)) expect(r).toEqual(m.vertices[v]);
  });
});

test.describe('a force\'s effect', () => {
  test.use({ example: 'sculpt.json' });
  test('is previewed where f0 is set: the panel says how far its middle moves, the arrow on the surface ends there, and the surface moves that far', async ({ page, studio }) => {
    await openStudio(page, studio);
    await clickPatch(page, 0);
    await expect(page.getByTestId('force-0')).toBeVisible();
    const force = (await model(studio)).frames[0].forces[0];
    const [lu, lv] = [force.region[1] - force.region[0], force.region[3] - force.region[2]];
    /** The seed's particular solution at the region's middle (a1 = a2 = 1 in the example). */
    const expected = (f0z: number) => -f0z / (Math.PI * Math.PI * (1 / (lu * lu) + 1 / (lv * lv)));
    type Arrow = { from: number[]; to: number[] } | null;
    const arrow = () => hook<Arrow>(page, 'forceEffect');
    const setF0z = async (text: string, value: number) => {
      await page.getByTestId('f0-z-value').fill(text);
      await page.getByTestId('f0-z-value').press('Enter');
      await expect.poll(async () => (await model(studio)).frames[0].forces[0].f0[2]).toBe(value);
      await settle(page);
    };
    // f0.z = 0: no arrow, the panel says the region does not move.
    await setF0z('0', 0);
    await expect(page.getByTestId('force-effect')).toHaveText('f0 is 0: the region does not move');
    await expect.poll(arrow).toBeNull();
    // f0.z = 40: toward -z by 40 / (pi^2 (1/Lu^2 + 1/Lv^2)), said and drawn.
    await setF0z('40', 40);
    const d = expected(40);
    await expect(page.getByTestId('force-effect')).toContainText('mostly toward −z');
    await expect(page.getByTestId('force-effect')).toContainText(`${Math.abs(d).toPrecision(3)} long`);
    await expect.poll(async () => (await arrow()) !== null).toBe(true);
    const a = (await arrow())!;
    expect(Math.abs(a.to[2] - a.from[2] - d)).toBeLessThan(ARROW_ROUNDING);
    expect(Math.abs(a.to[0] - a.from[0])).toBeLessThan(ARROW_ROUNDING);
    await page.screenshot({ path: shot('designer-force-effect.png') });
    // The arrow's tail is where the middle is without the force: at half the force the tip
    // (on the surface) moved half as far, and the tail stayed.
    await setF0z('20', 20);
    await expect.poll(async () => Math.abs((await arrow())?.to[2] ?? 0) > 0 && (await arrow())!.to[2] !== a.to[2]).toBe(true);
    const half = (await arrow())!;
    half.from.forEach((x, i) => expect(Math.abs(x - a.from[i])).toBeLessThan(FORCE_EFFECT_MATCH * Math.abs(d)));
  });
});

test('the pivot: each piece scaled about its own centre, then all turned about the active vertex', async ({ page, studio }) => {
  const m = await twoIslands(page, studio, 'pivot.json');
  const islands = m.frames.map((f: { vertices: number[] }) => new Set<number>(f.vertices));
  await page.keyboard.press('Control+a');
  await expect.poll(async () => (await selected(page)).length).toBe(m.vertices.length);
  // Each piece's centre: the islands double about (0.5, 0.5, 0) and (2.5, 0.5, 0).
  await page.getByTestId('selection-pivot').selectOption('pieces');
  await page.getByTestId('selection-scale').fill('2');
  await page.getByTestId('selection-scale-apply').click();
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  await settle(page);
  const scaled = m.vertices.map((p: number[], v: number) => {
    const c = islands[0].has(v) ? [0.5, 0.5, 0] : [2.5, 0.5, 0];
    return p.map((x, i) => c[i] + 2 * (x - c[i]));
  });
  // The active vertex: the right island's far corner (3, 1), now (3.5, 1.5), picked last
  // (shift+click takes it out of the selection, again puts it back last; the near corners of
  // the islands now stand at one place); a quarter turn of all about it.
  const corner = m.frames[1].vertices[4];
  const q = await hook<Point>(page, 'vertexScreen', corner);
  await page.keyboard.down('Shift');
  await page.mouse.click(q.x, q.y);
  await page.mouse.click(q.x, q.y);
  await page.keyboard.up('Shift');
  await expect.poll(async () => (await selected(page)).at(-1)).toBe(corner);
  expect((await selected(page)).length).toBe(m.vertices.length);
  await page.getByTestId('selection-pivot').selectOption('active');
  await page.getByTestId('selection-degrees').fill('90');
  await page.getByTestId('selection-rotate-apply').click();
  await expect.poll(async () => (await studio.state()).undo).toBe(3);
  await settle(page);
  await page.getByTestId('fit-all').click();
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('designer-pivot.png') });
  const file = await saved(page, studio, 'pivot.json');
  scaled.forEach((p: number[], v: number) => expect(close(file.vertices[v], turned(p, scaled[corner], 90))).toBe(true));
});
