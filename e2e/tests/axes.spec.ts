// The designer's transform tools of issue 27 not covered by designer.spec.ts, each checked in
// the saved file's numbers: the gizmo's rings (rotate) and boxes (scale) along the local axes
// of a turned frame and about the pivot; an axis-locked drag along the frame's own x and a
// move along the surface normal; X, Y or Z with snapping to vertices; Mirror across the plane
// through the model's centre; the effect arrows of a shared force.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { clickPatch, expect, newModel, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** What the studio computes from typed numbers and exact maps (a turn, a scale along an axis,
 * a projection) is exact to rounding. */
const ROUNDING = 1e-9;
/** The normal axis is the mesh's normal there, sent in single precision (about 6e-8). */
const MESH_NORMAL = 1e-6;
/** The effect arrows are the panel's formula applied to the file's numbers (rounding only). */
const ARROW_ROUNDING = 1e-9;
/** A ray meeting a plane (the cursor placed off the model) is on it to rounding, relative to
 * how far it went. */
const ON_PLANE = 1e-9;
/** A shared force's term is added to each of its patches: at half the f0 the arrows' tails
 * (the tips, on the surface, less the formula) stay put, to rounding (a fraction of the move). */
const FORCE_EFFECT_MATCH = 1e-9;

type Point = { x: number; y: number };
type Vec = number[];
const hook = <T>(page: Page, name: string, ...args: unknown[]) =>
  page.evaluate(([n, a]) => (window as any).__studio[n as string](...(a as unknown[])), [name, args] as const) as Promise<T>;
const model = async (studio: Studio) => (await studio.state()).model;
const sub = (a: Vec, b: Vec) => a.map((x, i) => x - b[i]);
const dot = (a: Vec, b: Vec) => a.reduce((s, x, i) => s + x * b[i], 0);
const norm = (a: Vec) => Math.sqrt(dot(a, a));
/** Leaves any box that has the focus (keys are keys again). */
const leaveBoxes = (page: Page) => page.locator('body').click({ position: { x: 5, y: 5 } });

async function drag(page: Page, from: Point, to: Point, keys: string[] = []): Promise<void> {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2, { steps: 3 });
  for (const k of keys) await page.keyboard.press(k);
  await page.mouse.move(to.x, to.y, { steps: 5 });
  await page.mouse.up();
  await settle(page);
}

/** The saved file of `name` in the studio's root, after Ctrl+S. */
async function saved(page: Page, studio: Studio, name: string) {
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  return JSON.parse(readFileSync(path.join(studio.root, name), 'utf8'));
}

/** A frame's own axes from its file numbers: u (slots 0 → 2 and 6 → 4), v made perpendicular,
 * their normal (web/src/orientation.ts frameBasis). */
function frameAxes(vertices: Vec[], ring: number[]): Vec[] {
  const p = (s: number) => vertices[ring[s]];
  const u = [0, 1, 2].map((c) => p(2)[c] - p(0)[c] + p(4)[c] - p(6)[c]);
  const v = [0, 1, 2].map((c) => p(6)[c] - p(0)[c] + p(4)[c] - p(2)[c]);
  const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const x = u.map((c) => c / norm(u)), z = n.map((c) => c / norm(n));
  return [x, [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]], z];
}

test.describe.configure({ timeout: 120_000 });

test("local axes: the gizmo's box scales a turned frame along its own x, its ring turns it about the pivot, X locks a drag to its x", async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'local.json');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await clickPatch(page, 0);
  // Turned 30° about z (Shift+R): its own axes are no longer x and y.
  await page.getByTestId('selection-degrees').fill('30');
  await page.locator('body').click({ position: { x: 5, y: 5 } }); // keys are keys again
  await clickPatch(page, 0);
  await page.keyboard.press('Shift+R');
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  await settle(page);
  const turned = await model(studio);
  const ring: number[] = turned.frames[0].vertices;
  const [x, y] = frameAxes(turned.vertices, ring);
  expect(Math.abs(x[0] - Math.cos(Math.PI / 6))).toBeLessThan(ROUNDING);

  // The scale gizmo on the local axes: its x box dragged outward along the frame's x.
  await page.getByTestId('orientation').selectOption('local');
  await page.keyboard.press('g');
  await page.keyboard.press('Shift+g');
  await page.keyboard.press('Shift+g');
  await expect(page.getByTestId('gizmo-mode')).toHaveValue('scale');
  await page.waitForTimeout(200);
  const box = (await hook<Point>(page, 'gizmoHandle', 'x'))!;
  const c = await hook<Point>(page, 'vertexScreen', ring[0]), e = await hook<Point>(page, 'vertexScreen', ring[4]);
  const centre = { x: (c.x + e.x) / 2, y: (c.y + e.y) / 2 };
  await drag(page, box, { x: box.x + 0.6 * (box.x - centre.x), y: box.y + 0.6 * (box.y - centre.y) });
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  let file = await saved(page, studio, 'local.json');
  // About the frame's centre: along x' each offset scaled by one factor, along y' and z none.
  const mid = [0, 1, 2].map((k) => (turned.vertices[ring[0]][k] + turned.vertices[ring[4]][k]) / 2);
  const factor = dot(sub(file.vertices[ring[2]], mid), x) / dot(sub(turned.vertices[ring[2]], mid), x);
  expect(factor).toBeGreaterThan(1.1);
  ring.forEach((v) => {
    const before = sub(turned.vertices[v], mid), after = sub(file.vertices[v], mid);
    expect(Math.abs(dot(after, x) - factor * dot(before, x))).toBeLessThan(ROUNDING);
    expect(Math.abs(dot(after, y) - dot(before, y))).toBeLessThan(ROUNDING);
    expect(Math.abs(after[2] - before[2])).toBeLessThan(ROUNDING);
  });
  await page.keyboard.press('Shift+F');
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('axes-scale-local.png') });

  // The rings, with the pivot on the origin: the gizmo sits there, the z ring dragged round
  // turns every vertex about the origin by one angle, z kept.
  const scaled = file.vertices as Vec[];
  await page.getByTestId('selection-pivot').selectOption('origin');
  await page.getByTestId('gizmo-mode').selectOption('rotate');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.waitForTimeout(200);
  const from = (await hook<Point>(page, 'gizmoHandle', 'z', Math.PI / 4))!; // off the x and y rings (edge-on here)
  const to = (await hook<Point>(page, 'gizmoHandle', 'z', Math.PI / 4 + 2))!;
  await drag(page, from, to);
  await expect.poll(async () => (await studio.state()).undo).toBe(3);
  file = await saved(page, studio, 'local.json');
  const angle = (p: Vec) => Math.atan2(p[1], p[0]);
  const turn = angle(file.vertices[ring[4]]) - angle(scaled[ring[4]]);
  expect(Math.abs(turn)).toBeGreaterThan(0.02);
  ring.forEach((v) => {
    const p = file.vertices[v], q = scaled[v];
    expect(Math.abs(Math.hypot(p[0], p[1]) - Math.hypot(q[0], q[1]))).toBeLessThan(ROUNDING);
    expect(Math.abs(p[2] - q[2])).toBeLessThan(ROUNDING);
    const t = Math.atan2(Math.sin(angle(p) - angle(q) - turn), Math.cos(angle(p) - angle(q) - turn));
    if (Math.hypot(q[0], q[1]) > 0.1) expect(Math.abs(t)).toBeLessThan(ROUNDING);
  });
  await page.keyboard.press('Shift+F');
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('axes-rotate-ring.png') });

  // X during a handle drag locks it to the frame's own x (the panel's local axes).
  await page.keyboard.press('g'); // the gizmo off: nothing over the handles
  const axes = frameAxes(file.vertices, ring);
  const corner = ring[4];
  const q = await hook<Point>(page, 'vertexScreen', corner);
  await page.mouse.move(q.x, q.y);
  await page.mouse.down();
  await page.mouse.move(q.x + 20, q.y - 30, { steps: 3 });
  await page.keyboard.press('x');
  await expect(page.getByTestId('status')).toContainText('along local x only');
  await page.mouse.move(q.x + 50, q.y - 70, { steps: 5 });
  await page.mouse.up();
  await settle(page);
  const locked = await saved(page, studio, 'local.json');
  const d = sub(locked.vertices[corner], file.vertices[corner]);
  expect(norm(d)).toBeGreaterThan(0.05);
  expect(Math.abs(dot(d, axes[1]))).toBeLessThan(ROUNDING);
  expect(Math.abs(dot(d, axes[2]))).toBeLessThan(ROUNDING);

  // The help lists the gizmo's handles and the axes (docs/images/studio-help.png).
  await page.keyboard.press('?');
  await page.getByTestId('help-keys').locator('kbd', { hasText: /^Shift\+G$/ }).scrollIntoViewIfNeeded();
  await expect(page.getByTestId('help')).toContainText('drag a ring / a box of the gizmo');
  await expect(page.getByTestId('help')).toContainText('Shift+right-click in either view');
  await expect(page.getByTestId('help-panel')).toContainText('a number or an expression');
  await page.screenshot({ path: shot('axes-help.png') });
  await page.keyboard.press('Escape');
});

/** Shift+right-click at a client point (places the 3D cursor). */
async function placeCursor(page: Page, at: Point): Promise<void> {
  await page.keyboard.down('Shift');
  await page.mouse.click(at.x, at.y, { button: 'right' });
  await page.keyboard.up('Shift');
}
type Cursor = { p: Vec; frame: Point & { visible: boolean } };
const cursorOf = (page: Page) => hook<Cursor>(page, 'cursor');

test('the 3D cursor: placed on the surface by Shift+right-click, typed, to the selection; Shift+R, the rings and boxes pivot on it; kept over a reload, never in the file', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'cursor.json');
  const start = await model(studio);
  const ring: number[] = start.frames[0].vertices;
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(300);
  const screen = (v: number) => hook<Point>(page, 'vertexScreen', v);
  const [c0, c4] = [await screen(ring[0]), await screen(ring[4])];

  // On the surface: a third of the way along the patch's diagonal, the point of the surface
  // under the pointer (the flat patch: z = 0).
  const on = { x: Math.round(c0.x + (c4.x - c0.x) / 3), y: Math.round(c0.y + (c4.y - c0.y) / 3) };
  const under = (await hook<Vec | null>(page, 'surfaceUnder', on.x, on.y))!;
  await placeCursor(page, on);
  await expect.poll(async () => (await cursorOf(page)).p).toEqual(under);
  expect(Math.abs(under[2])).toBeLessThan(ROUNDING);
  expect(under[0]).toBeGreaterThan(0.1);
  expect(under[0]).toBeLessThan(0.6);
  await expect(page.getByTestId('cursor-x')).toHaveValue(String(+under[0].toFixed(6)));
  expect(await page.evaluate(() => (window as any).__studio.selection().frames)).toEqual([]); // no pan, no pick
  // Off the model (the view's top left): in the plane through the cursor facing the camera.
  const box = (await page.getByTestId('frame-view').boundingBox())!;
  await placeCursor(page, { x: box.x + 40, y: box.y + 60 });
  const off = (await cursorOf(page)).p;
  const facing = (await hook<{ frame: { direction: Vec } }>(page, 'cameras')).frame.direction;
  expect(norm(sub(off, under))).toBeGreaterThan(0.3);
  expect(Math.abs(dot(sub(off, under), facing))).toBeLessThan(ON_PLANE * norm(sub(off, under)));

  // Typed, as expressions: (1, 1/2, 0), the middle of the frame's right side. A quarter turn
  // (Shift+R) about it with the pivot on the cursor: exact numbers.
  for (const [axis, text] of [['x', '2/2'], ['y', '1/2'], ['z', '0']]) {
    await page.getByTestId(`cursor-${axis}`).fill(text);
    await page.getByTestId(`cursor-${axis}`).press('Enter');
  }
  const cursor = [1, 0.5, 0];
  await expect.poll(async () => (await cursorOf(page)).p).toEqual(cursor);
  await page.getByTestId('selection-pivot').selectOption('cursor');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await page.getByTestId('selection-degrees').fill('90');
  await leaveBoxes(page);
  await clickPatch(page, 0);
  await page.keyboard.press('Shift+R');
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  await settle(page);
  let file = await saved(page, studio, 'cursor.json');
  start.vertices.forEach((p: Vec, v: number) => expect(file.vertices[v]).toEqual([1 - (p[1] - 0.5), 0.5 + (p[0] - 1), p[2]]));

  // The rings stand on the cursor; the z ring dragged round turns the frame about it.
  await page.keyboard.press('g');
  await page.keyboard.press('Shift+g');
  await expect(page.getByTestId('gizmo-mode')).toHaveValue('rotate');
  await page.getByTestId('fit-all').click();
  await page.waitForTimeout(400);
  const [r0, r1] = [(await hook<Point>(page, 'gizmoHandle', 'z', 0))!, (await hook<Point>(page, 'gizmoHandle', 'z', Math.PI))!];
  const mark = (await cursorOf(page)).frame;
  expect(Math.hypot((r0.x + r1.x) / 2 - mark.x, (r0.y + r1.y) / 2 - mark.y)).toBeLessThan(1);
  await drag(page, (await hook<Point>(page, 'gizmoHandle', 'z', Math.PI / 4))!, (await hook<Point>(page, 'gizmoHandle', 'z', Math.PI / 4 + 1.5))!);
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  const quarter = file.vertices as Vec[];
  file = await saved(page, studio, 'cursor.json');
  const angle = (p: Vec) => Math.atan2(p[1] - cursor[1], p[0] - cursor[0]);
  const turn = angle(file.vertices[ring[0]]) - angle(quarter[ring[0]]);
  expect(Math.abs(turn)).toBeGreaterThan(0.1);
  ring.forEach((v) => {
    const p = file.vertices[v], q = quarter[v];
    expect(Math.abs(norm(sub(p, cursor)) - norm(sub(q, cursor)))).toBeLessThan(ROUNDING);
    expect(Math.abs(p[2] - q[2])).toBeLessThan(ROUNDING);
    const t = Math.atan2(Math.sin(angle(p) - angle(q) - turn), Math.cos(angle(p) - angle(q) - turn));
    if (norm(sub(q, cursor)) > 0.1) expect(Math.abs(t)).toBeLessThan(ROUNDING); // the one on the cursor stays
  });

  await page.getByTestId('fit-all').click();
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('axes-cursor.png') });

  // The boxes on the cursor too: the x box dragged outward scales x offsets from it alone.
  await page.keyboard.press('Shift+g');
  await expect(page.getByTestId('gizmo-mode')).toHaveValue('scale');
  await page.waitForTimeout(200);
  const centre = (await cursorOf(page)).frame;
  const xBox = (await hook<Point>(page, 'gizmoHandle', 'x'))!;
  await drag(page, xBox, { x: xBox.x + 0.5 * (xBox.x - centre.x), y: xBox.y });
  await expect.poll(async () => (await studio.state()).undo).toBe(3);
  const turnedAbout = file.vertices as Vec[];
  file = await saved(page, studio, 'cursor.json');
  const far = ring.reduce((a, b) => (Math.abs(turnedAbout[b][0] - 1) > Math.abs(turnedAbout[a][0] - 1) ? b : a));
  const factor = (file.vertices[far][0] - 1) / (turnedAbout[far][0] - 1);
  expect(factor).toBeGreaterThan(1.1);
  ring.forEach((v) => {
    const p = file.vertices[v], q = turnedAbout[v];
    expect(Math.abs(p[0] - 1 - factor * (q[0] - 1))).toBeLessThan(ROUNDING);
    expect(Math.abs(p[1] - q[1])).toBeLessThan(ROUNDING);
    expect(Math.abs(p[2] - q[2])).toBeLessThan(ROUNDING);
  });

  // To the selection: the centre of the frame's box; to the origin.
  await page.getByTestId('cursor-to-selection').click();
  const xs = ring.map((v) => file.vertices[v][0]), ys = ring.map((v) => file.vertices[v][1]);
  await expect.poll(async () => (await cursorOf(page)).p).toEqual([(Math.min(...xs) + Math.max(...xs)) / 2, (Math.min(...ys) + Math.max(...ys)) / 2, 0]);
  await page.getByTestId('cursor-to-origin').click();
  await expect.poll(async () => (await cursorOf(page)).p).toEqual([0, 0, 0]);

  // Kept by the browser for this file over a reload; the model file never holds it.
  await page.getByTestId('cursor-y').fill('-1/4');
  await page.getByTestId('cursor-y').press('Enter');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect.poll(async () => (await cursorOf(page)).p).toEqual([0, -0.25, 0]);
  await expect(page.getByTestId('cursor-y')).toHaveValue('-0.25');
  expect(readFileSync(path.join(studio.root, 'cursor.json'), 'utf8')).not.toContain('cursor');
});

test('normal axes: the selection moved by dz goes along the surface normal of a tilted frame', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'normal.json');
  await page.getByTestId('view-iso').click();
  await clickPatch(page, 0);
  // Tilted 30° about x: its normal is (0, -sin 30°, cos 30°) (a flat frame: the surface's too).
  await page.getByTestId('selection-axis').selectOption('x');
  await page.getByTestId('selection-degrees').fill('30');
  await page.getByTestId('selection-rotate-apply').click();
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  await settle(page);
  const tilted = await model(studio);
  await page.getByTestId('orientation').selectOption('normal');
  await page.getByTestId('offset-z').fill('1/4');
  await page.getByTestId('offset-apply').click();
  await expect.poll(async () => (await studio.state()).undo).toBe(2);
  const file = await saved(page, studio, 'normal.json');
  const n = [0, -Math.sin(Math.PI / 6), Math.cos(Math.PI / 6)];
  const sign = Math.sign(dot(sub(file.vertices[0], tilted.vertices[0]), n));
  tilted.vertices.forEach((p: Vec, v: number) => {
    const d = sub(file.vertices[v], p);
    d.forEach((x, k) => expect(Math.abs(x - sign * 0.25 * n[k])).toBeLessThan(0.25 * MESH_NORMAL));
  });
});

test("on two frames: X with snapping to vertices lines the corner up with the vertex under the pointer; Mirror across the plane through the model's centre", async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'two.json', 2, 1);
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  const m = await model(studio);
  const at = (p: Vec) => m.vertices.findIndex((q: Vec) => q.every((x, k) => Math.abs(x - p[k]) < ROUNDING));
  const xs = m.vertices.map((p: Vec) => p[0]), ys = m.vertices.map((p: Vec) => p[1]);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const centre = (x0 + x1) / 2; // the two frames' shared side

  // The right frame's far corner dragged with X pressed and snapping to vertices, released
  // 3 px off the left frame's bottom middle: it takes that vertex's x exactly, y and z kept.
  const corner = at([x1, y1, 0]);
  const target = at([(x0 + centre) / 2, y0, 0]);
  expect(Math.min(corner, target)).toBeGreaterThanOrEqual(0);
  await page.getByTestId('snap-to').selectOption('vertices');
  const p = await hook<Point>(page, 'vertexScreen', corner);
  const t = await hook<Point>(page, 'vertexScreen', target);
  await drag(page, p, { x: t.x + 3, y: t.y - 2 }, ['x']);
  let file = await saved(page, studio, 'two.json');
  expect(file.vertices[corner]).toEqual([m.vertices[target][0], y1, 0]);
  file.vertices.forEach((q: Vec, v: number) => v === corner || expect(q).toEqual(m.vertices[v]));
  expect((await studio.state()).undo).toBe(1);
  await page.screenshot({ path: shot('axes-lock-snap.png') });
  await page.getByTestId('snap-to').selectOption('off');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await studio.state()).undo).toBe(0);
  await settle(page);

  // A third frame extruded up from the left one's top side, then mirrored (M) across x
  // through the centre of the model's box (x from x0 to x1 still): it lands on the right.
  for (const [i, v] of [at([x0, y1, 0]), at([centre, y1, 0])].entries()) {
    const q = await hook<Point>(page, 'vertexScreen', v);
    if (i) await page.keyboard.down('Shift');
    await page.mouse.click(q.x, q.y);
    if (i) await page.keyboard.up('Shift');
  }
  await expect.poll(async () => (await hook<{ vertices: number[] }>(page, 'selection')).vertices.length).toBe(2);
  await page.keyboard.press('e');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(3);
  await settle(page);
  const before = await model(studio);
  const seam = [...new Set<number>(before.frames[2].vertices.filter((v: number) => Math.abs(before.vertices[v][0] - centre) < ROUNDING))];
  expect(seam).toHaveLength(3);
  await page.getByTestId('symmetry').selectOption('cx');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await clickPatch(page, 2);
  await page.keyboard.press('m');
  await expect.poll(async () => (await model(studio)).frames.length).toBe(4);
  await page.keyboard.press('Shift+F');
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('axes-mirror-centre.png') });
  file = await saved(page, studio, 'two.json');
  // The copy uses the seam's 3 vertices themselves; its 5 others are new, at 2 centre − x.
  const copy = new Set<number>(file.frames[3].vertices);
  expect([...copy].filter((v) => seam.includes(v)).sort()).toEqual(seam.sort());
  expect(file.vertices).toHaveLength(before.vertices.length + 5);
  for (const q of file.vertices.slice(before.vertices.length)) {
    expect(q[0]).toBeGreaterThan(centre);
    const image = [2 * centre - q[0], q[1], q[2]];
    expect(before.frames[2].vertices.some((v: number) => before.vertices[v].every((x: number, k: number) => Math.abs(x - image[k]) < ROUNDING))).toBe(true);
  }
  expect((await studio.state()).undo).toBe(2);
});

test.describe('a shared force', () => {
  test.use({ example: 'grid-forces.json' });
  test("has an effect arrow on each of its frames' patches: the formula with each frame's a1, a2, its tail where the middle is without the force", async ({ page, studio }) => {
    await openStudio(page, studio);
    await page.getByTestId('view-iso').click();
    const m = await model(studio);
    const force = m.forces[0];
    const frames = [...force.frames].sort((a: number, b: number) => a - b);
    for (const [i, f] of frames.entries()) await clickPatch(page, f, i > 0);
    await expect(page.getByTestId('shared-force')).toContainText(`shared force over frames ${frames.join(', ')}`);
    type Arrow = { frame: number; from: Vec; to: Vec };
    const arrows = () => hook<Arrow[]>(page, 'sharedForceEffects');
    await expect.poll(async () => (await arrows()).length).toBe(frames.length);
    /** The formula per frame: a shared force acts on each frame whole (Lu = Lv = 1). */
    const expected = (f0: Vec, k: number) => {
      const a1 = m.frames[k].a1 ?? [1, 1, 1], a2 = m.frames[k].a2 ?? [1, 1, 1];
      return f0.map((x: number, c: number) => (x === 0 ? 0 : -x / (Math.PI * Math.PI * (a1[c] + a2[c]))));
    };
    const first = await arrows();
    for (const a of first) sub(a.to, a.from).forEach((x, c) => expect(Math.abs(x - expected(force.f0, a.frame)[c])).toBeLessThan(ARROW_ROUNDING));
    await expect(page.getByTestId('force-effect')).toContainText(`on each of its ${frames.length} frames its middle moves by`);
    await page.screenshot({ path: shot('axes-shared-force.png') });
    // Half the f0 (typed): the tips move half the way back, the tails stay.
    const half = force.f0[2] / 2;
    await page.getByTestId('f0-z-value').fill(String(half));
    await page.getByTestId('f0-z-value').press('Enter');
    await expect.poll(async () => (await model(studio)).forces[0].f0[2]).toBe(half);
    await settle(page);
    await expect.poll(async () => (await arrows())[0]?.to[2] !== first[0].to[2]).toBe(true);
    const now = await arrows();
    now.forEach((a, i) => {
      const length = norm(sub(first[i].to, first[i].from));
      a.from.forEach((x, c) => expect(Math.abs(x - first[i].from[c])).toBeLessThan(FORCE_EFFECT_MATCH * length));
    });
    await page.locator('body').click({ position: { x: 5, y: 5 } }); // keys are keys again
    const file = await saved(page, studio, 'grid-forces.json');
    expect(file.forces[0].f0[2]).toBe(half);
  });
});
