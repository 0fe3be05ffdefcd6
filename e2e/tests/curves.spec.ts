// Whole curves and tangents of spectral and B-spline PDE models, as a user edits them: click a
// curve's centre mark to choose it, drag the move gizmo's arrow (G) or the mark itself, turn
// and scale it with Shift+R and Shift+S; drag a tangent's tip; drag a blend's curve points
// and its shared corner. The saved file's numbers are checked against what each edit must do
// (a Fourier curve moved by d: a0 + d, its modes unchanged; turned a quarter about z: its
// coefficient vectors turned), and undo gives the file back byte for byte.
import { readFileSync } from 'node:fs';
import type { Page } from '@playwright/test';
import { expect, meshUpToDate, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** What the studio computes from typed numbers (a quarter turn, a scale) is exact to rounding
 * (the file keeps shortest round-trip numbers); 1e-12 of these unit-sized models is far
 * above rounding and far below any real miss. */
const ROUNDING = 1e-12;
/** A handle the page places from the file (a tangent's tip, a centre) is there to rounding. */
const THROUGH = 1e-9;
/** src/shape.ts: a tangent's tip is drawn at base + TANGENT_DRAW × vector. */
const TANGENT_DRAW = 0.25;

type Point = { x: number; y: number };
type Handle = { kind: string; curve?: number | string; point?: number; p: number[]; base?: number[]; x: number; y: number; visible: boolean };
type Centre = { curve: number | string; p: number[]; x: number; y: number; visible: boolean };
type V = number[];

const handles = (page: Page): Promise<Handle[]> => page.evaluate(() => (window as any).__shape.handles());
const centres = (page: Page): Promise<Centre[]> => page.evaluate(() => (window as any).__shape.centres());
const centreOf = async (page: Page, curve: number | string) => (await centres(page)).find((c) => c.curve === curve)!;
const fileText = (studio: Studio) => readFileSync(studio.model, 'utf8');
const fileJson = (studio: Studio) => JSON.parse(fileText(studio));
const sub = (a: V, b: V) => a.map((x, c) => x - b[c]);
const distance = (a: V, b: V) => Math.hypot(...sub(a, b));
const undoDepth = async (studio: Studio) => (await studio.state()).undo;

async function drag(page: Page, from: Point, to: Point): Promise<void> {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps: 8 });
  await page.mouse.up();
  await settle(page);
}

async function save(page: Page): Promise<void> {
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
}

/** Ctrl+Z `times` times (each answered before the next), then saved. */
async function undoAll(page: Page, studio: Studio, times: number): Promise<void> {
  for (let i = 0; i < times; ++i) {
    await expect(page.getByTestId('undo')).toBeEnabled();
    const depth = await undoDepth(studio);
    await page.keyboard.press('Control+z');
    await expect.poll(() => undoDepth(studio)).toBe(depth - 1);
  }
  await page.keyboard.press('Control+s');
}

/** Clicks the centre mark of `curve` (again until the page has chosen it: a click can be lost
 * while software WebGL renders). */
async function chooseCurve(page: Page, curve: number | string, label: string): Promise<void> {
  await expect(async () => {
    const c = await centreOf(page, curve);
    expect(c.visible).toBe(true);
    await page.mouse.click(c.x, c.y);
    await expect(page.getByTestId('curve-select')).toHaveValue(String(curve), { timeout: 1000 });
  }).toPass({ timeout: 30000 });
  await expect(page.getByTestId('shape-handle')).toHaveText(`${label}, whole`);
}

/** Leaves any box that has the focus (keys are keys again). */
const leaveBoxes = (page: Page) => page.locator('body').click({ position: { x: 5, y: 5 } });

// Many user steps in software WebGL: more time than the default 60 s.
test.describe.configure({ timeout: 240_000 });

test.describe('a Fourier curve (the membrane)', () => {
  test.use({ example: 'membrane.json' });

  test('G and its x arrow, Shift+R a quarter turn, a drag of its centre: a0 and the modes as they must be; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    const was = JSON.parse(original).conditions[4].curve.fourier; // u = 0.8, a0 = (0, 0, 1.6)
    await openStudio(page, studio);
    await page.getByTestId('view-front').click(); // x to the right, z up
    await page.waitForTimeout(400);
    // Derivative conditions are vectors: no centre mark; the four position curves have one.
    expect((await centres(page)).map((c) => c.curve)).toEqual([0, 1, 4, 7]);
    await chooseCurve(page, 4, 'condition 4 (u = 0.8)');
    await page.keyboard.press('g');
    await expect.poll(() => page.evaluate(() => (window as any).__studio.gizmoArrow('x'))).not.toBeNull();
    const arrow = await page.evaluate(() => (window as any).__studio.gizmoArrow('x') as Point);
    await page.waitForTimeout(200);
    await drag(page, arrow, { x: arrow.x + 80, y: arrow.y - 25 }); // off the axis: only x counts
    expect(await undoDepth(studio)).toBe(1); // one drag, one undo step
    await meshUpToDate(page);
    await save(page);
    let now = fileJson(studio).conditions[4].curve.fourier;
    const dx = now.a0[0] - was.a0[0];
    expect(dx).toBeGreaterThan(0.05);
    expect(now.a0.slice(1)).toEqual(was.a0.slice(1)); // along x alone
    expect(now.a).toEqual(was.a); // the modes are directions: a move leaves them
    expect(now.b).toEqual(was.b);
    // The gizmo and the centre mark follow the curve.
    await expect.poll(async () => distance((await centreOf(page, 4)).p, now.a0)).toBeLessThan(THROUGH);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('curve-gizmo.png') });
    await page.keyboard.press('g');

    // Shift+R: a quarter turn about z through the curve's centre (a0): a0 stays, each
    // coefficient vector (x, y, z) → (−y, x, z).
    await page.getByTestId('curve-rotate-degrees').fill('90');
    await page.getByTestId('curve-rotate-axis').selectOption('z');
    await leaveBoxes(page);
    await page.keyboard.press('Shift+R');
    await expect.poll(() => undoDepth(studio)).toBe(2);
    await save(page);
    const turned = fileJson(studio).conditions[4].curve.fourier;
    expect(distance(turned.a0, now.a0)).toBeLessThan(ROUNDING);
    const quarter = (v: V) => [-v[1], v[0], v[2]];
    now.a.forEach((v: V, n: number) => expect(distance(turned.a[n], quarter(v))).toBeLessThan(ROUNDING));
    now.b.forEach((v: V, n: number) => expect(distance(turned.b[n], quarter(v))).toBeLessThan(ROUNDING));
    // The other conditions are untouched.
    const all = fileJson(studio).conditions;
    JSON.parse(original).conditions.forEach((c: any, i: number) => i === 4 || expect(all[i]).toEqual(c));

    // The centre mark dragged in the screen's plane: a0 moves, the modes stay exactly.
    const mark = await centreOf(page, 4);
    await drag(page, mark, { x: mark.x - 40, y: mark.y - 30 });
    expect(await undoDepth(studio)).toBe(3);
    await meshUpToDate(page);
    await save(page);
    now = fileJson(studio).conditions[4].curve.fourier;
    expect(distance(now.a0, turned.a0)).toBeGreaterThan(0.05);
    expect(now.a0[0]).toBeLessThan(turned.a0[0]); // left on screen: −x
    expect(now.a0[2]).toBeGreaterThan(turned.a0[2]); // up on screen: +z
    expect(now.a).toEqual(turned.a);
    expect(now.b).toEqual(turned.b);

    await undoAll(page, studio, 3);
    await expect.poll(() => fileText(studio)).toBe(original);

    // The help (?) says what G, Shift+R and Shift+S do to a chosen curve, and what the
    // centre marks and tangent tips do; scrolled to them for the user guide's picture.
    await page.keyboard.press('?');
    const help = page.getByTestId('help');
    await expect(help).toBeVisible();
    for (const [key, what] of [['G', 'chosen curve'], ['Shift+R', 'chosen curve'], ['Shift+S', 'chosen curve']])
      await expect(page.getByTestId('help-keys').locator('tr', { has: page.locator('kbd', { hasText: new RegExp(`^${key.replace('+', '\\+')}$`) }) })).toContainText(what);
    await expect(help).toContainText("click / drag a curve's centre mark");
    await expect(help).toContainText("a tangent's tip");
    await help.evaluate((el) => {
      const row = Array.from(el.querySelectorAll('kbd')).find((k) => k.textContent === 'N')!;
      el.scrollTop = (row as HTMLElement).getBoundingClientRect().top - el.getBoundingClientRect().top + el.scrollTop - 40;
    });
    await page.waitForTimeout(200);
    await page.screenshot({ path: shot('curve-help.png') });
  });
});

test.describe('a Fourier tangent (the membrane\'s first derivative at u = 0.2)', () => {
  test.use({ example: 'membrane.json' });

  test('drag its tip: a0 = (tip − centre) / 0.25, the modes unchanged; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    const was = JSON.parse(original).conditions[2].curve.fourier; // u = 0.2, ∂u, a0 = (0, 0, 2)
    await openStudio(page, studio);
    await page.getByTestId('view-front').click();
    await page.waitForTimeout(400);
    // One tip per first-derivative condition (2 and 5), from its position curve's centre.
    const tips = (await handles(page)).filter((h) => h.kind === 'tangent');
    expect(tips.map((h) => h.curve)).toEqual([2, 5]);
    const h = tips[0];
    expect(distance(h.base!, JSON.parse(original).conditions[1].curve.fourier.a0)).toBe(0);
    expect(distance(h.p, h.base!.map((x, c) => x + TANGENT_DRAW * was.a0[c]))).toBeLessThan(THROUGH);
    await drag(page, h, { x: h.x + 40, y: h.y });
    await meshUpToDate(page);
    await expect(page.getByTestId('shape-handle')).toHaveText('curve 2, mean tangent (a0)');
    await page.screenshot({ path: shot('curve-mean-tangent.png') });
    await save(page);
    const now = fileJson(studio).conditions[2].curve.fourier;
    expect(now.a0[0]).toBeGreaterThan(0.1); // tilted toward +x (right on screen)
    expect(now.a).toEqual(was.a);
    expect(now.b).toEqual(was.b);
    const after = (await handles(page)).find((t) => t.kind === 'tangent' && t.curve === 2)!;
    expect(distance(after.p, after.base!.map((x, c) => x + TANGENT_DRAW * now.a0[c]))).toBeLessThan(THROUGH);
    await undoAll(page, studio, 1);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a curve of points (the shell)', () => {
  test.use({ example: 'shell.json' });

  test('its centre dragged moves every point by the same offset; Shift+S scales it about its centre; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    const was: V[] = JSON.parse(original).conditions[5].curve.points;
    await openStudio(page, studio);
    await chooseCurve(page, 5, 'condition 5 (u = ' + JSON.parse(original).conditions[5].u + ')');
    const mark = await centreOf(page, 5);
    await drag(page, mark, { x: mark.x + 35, y: mark.y - 25 });
    expect(await undoDepth(studio)).toBe(1);
    await meshUpToDate(page);
    await save(page);
    const moved: V[] = fileJson(studio).conditions[5].curve.points;
    const d = sub(moved[0], was[0]);
    expect(Math.hypot(...d)).toBeGreaterThan(0.02);
    moved.forEach((p, k) => expect(distance(sub(p, was[k]), d)).toBeLessThan(ROUNDING));
    // The centre mark is the mean of the file's points.
    const mean = [0, 1, 2].map((c) => moved.reduce((s, p) => s + p[c], 0) / moved.length);
    await expect.poll(async () => distance((await centreOf(page, 5)).p, mean)).toBeLessThan(THROUGH);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('curve-centre-drag.png') });

    // Shift+S by 1.5 about the mean of its points.
    await page.getByTestId('curve-scale-factor').fill('1.5');
    await leaveBoxes(page);
    await page.keyboard.press('Shift+S');
    await expect.poll(() => undoDepth(studio)).toBe(2);
    await save(page);
    const scaled: V[] = fileJson(studio).conditions[5].curve.points;
    const centre = [0, 1, 2].map((c) => moved.reduce((s, p) => s + p[c], 0) / moved.length);
    scaled.forEach((p, k) => expect(distance(p, centre.map((x, c) => x + 1.5 * (moved[k][c] - x)))).toBeLessThan(ROUNDING));
    await undoAll(page, studio, 2);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a B-spline PDE boundary with tangent rows (the dome)', () => {
  test.use({ example: 'bspline-dome.json' });

  test("drag a tangent's tip: the file's vector is (tip − base) / 0.25, the others unchanged; undo", async ({ page, studio }) => {
    const original = fileText(studio);
    const was: V[] = JSON.parse(original).boundary.uMinSecond.tangent.points;
    await openStudio(page, studio);
    const tips = (await handles(page)).filter((h) => h.kind === 'tangent' && h.curve === 'uMinSecond');
    expect(tips).toHaveLength(was.length);
    // Each tip is drawn where the file's vector puts it, from the side u = 0.
    tips.forEach((h) => expect(distance(h.p, h.base!.map((x, c) => x + TANGENT_DRAW * was[h.point!][c]))).toBeLessThan(THROUGH));
    const h = tips.filter((t) => t.visible)[Math.floor(tips.length / 2)];
    await drag(page, h, { x: h.x + 30, y: h.y - 30 });
    await meshUpToDate(page);
    await expect(page.getByTestId('shape-handle')).toHaveText(`uMinSecond, tangent ${h.point}`);
    await page.screenshot({ path: shot('curve-tangent.png') });
    await save(page);
    const now: V[] = fileJson(studio).boundary.uMinSecond.tangent.points;
    expect(distance(now[h.point!], was[h.point!])).toBeGreaterThan(0.05);
    now.forEach((v, k) => k === h.point || expect(v).toEqual(was[k]));
    const after = (await handles(page)).find((t) => t.kind === 'tangent' && t.curve === 'uMinSecond' && t.point === h.point)!;
    expect(distance(after.p, after.base!.map((x, c) => x + TANGENT_DRAW * now[h.point!][c]))).toBeLessThan(THROUGH);
    await undoAll(page, studio, 1);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a B-spline PDE blend (seed 004 Example 4)', () => {
  test.use({ example: 'bspline-blend.json' });

  test('drag a curve point, a shared corner and a whole curve: the file\'s curves; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    const blend = JSON.parse(original).blend;
    await openStudio(page, studio);
    await page.getByTestId('view-top').click(); // x to the right, y up: the four curves apart
    await page.waitForTimeout(400);
    const find = async (curve: string, point: number) => (await handles(page)).find((h) => h.kind === 'curve' && h.curve === curve && h.point === point)!;

    // An inner point of uMin, dragged: that point alone (point 3 is under uMin's centre mark
    // in this view).
    const inner = await find('uMin', 2);
    await drag(page, inner, { x: inner.x - 40, y: inner.y });
    await meshUpToDate(page);
    await page.screenshot({ path: shot('curve-blend-point.png') });
    await save(page);
    let now = fileJson(studio).blend;
    expect(distance(now.uMin.bspline[2], blend.uMin.bspline[2])).toBeGreaterThan(0.05);
    now.uMin.bspline.forEach((p: V, k: number) => k === 2 || expect(p).toEqual(blend.uMin.bspline[k]));
    for (const name of ['uMax', 'vMin', 'vMax']) expect(now[name].bspline).toEqual(blend[name].bspline); // (the saved file writes their knots out)

    // The corner (0, 0, 0) that uMin and vMin share: both ends follow.
    const corner = await find('vMin', 0);
    await drag(page, corner, { x: corner.x - 30, y: corner.y + 30 });
    await save(page);
    now = fileJson(studio).blend;
    expect(distance(now.vMin.bspline[0], blend.vMin.bspline[0])).toBeGreaterThan(0.05);
    expect(now.uMin.bspline[0]).toEqual(now.vMin.bspline[0]);

    // vMax whole, by its centre mark: every point by one offset, and the corners it shares
    // with uMin and uMax with it.
    await chooseCurve(page, 'vMax', 'vMax');
    const mark = await centreOf(page, 'vMax');
    await drag(page, mark, { x: mark.x + 20, y: mark.y - 40 });
    await meshUpToDate(page);
    await save(page);
    now = fileJson(studio).blend;
    // The page shows the file's curves again (the shared corner in uMin too).
    await expect.poll(async () => distance((await find('uMin', now.uMin.bspline.length - 1)).p, now.uMin.bspline.at(-1))).toBeLessThan(THROUGH);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('curve-blend-whole.png') });
    const d = sub(now.vMax.bspline[0], blend.vMax.bspline[0]);
    expect(Math.hypot(...d)).toBeGreaterThan(0.05);
    now.vMax.bspline.forEach((p: V, k: number) => expect(distance(sub(p, blend.vMax.bspline[k]), d)).toBeLessThan(ROUNDING));
    expect(now.uMin.bspline.at(-1)).toEqual(now.vMax.bspline[0]);
    expect(now.uMax.bspline.at(-1)).toEqual(now.vMax.bspline.at(-1));
    expect(await undoDepth(studio)).toBe(3);

    await undoAll(page, studio, 3);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a section of the vase, the pivot on the 3D cursor', () => {
  test.use({ example: 'vase-sections.json' });

  test("the gizmo's z ring turns the chosen section about the cursor, its x box scales it along x from it: the file's points; one undo step each; undone byte for byte", async ({ page, studio }) => {
    const original = fileText(studio);
    const was = JSON.parse(original).curves as { points: V[] }[];
    await openStudio(page, studio);
    await page.getByTestId('curve-select').selectOption('6');
    // The cursor on the section's centre, then a tenth to the side (typed as an expression).
    await page.getByTestId('cursor-to-selection').click();
    const cursorOf = async () => (await page.evaluate(() => (window as any).__studio.cursor())).p as V;
    const centre = [0, 1, 2].map((c) => was[6].points.reduce((s, p) => s + p[c], 0) / was[6].points.length);
    await expect.poll(async () => distance(await cursorOf(), centre)).toBeLessThan(THROUGH);
    const x = await page.getByTestId('cursor-x').inputValue();
    await page.getByTestId('cursor-x').fill(`${x} + 1/10`);
    await page.getByTestId('cursor-x').press('Enter');
    await expect.poll(async () => (await cursorOf())[0]).toBe(Number(x) + 0.1);
    const cursor = await cursorOf();
    await page.getByTestId('selection-pivot').selectOption('cursor');
    await page.getByTestId('view-top').click();
    await page.waitForTimeout(400);
    await leaveBoxes(page);
    await page.keyboard.press('g');
    await page.keyboard.press('Shift+g');
    await expect(page.getByTestId('gizmo-mode')).toHaveValue('rotate');
    await page.waitForTimeout(200);
    const ring = (angle: number) => page.evaluate((a) => (window as any).__studio.gizmoHandle('z', a), angle) as Promise<Point>;
    await drag(page, await ring(Math.PI / 4), await ring(Math.PI / 4 + 0.8));
    await expect.poll(() => undoDepth(studio)).toBe(1);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('curves-cursor-ring.png') });
    await save(page);
    const turned = fileJson(studio).curves as { points: V[] }[];
    const angle = (p: V) => Math.atan2(p[1] - cursor[1], p[0] - cursor[0]);
    const turn = angle(turned[6].points[0]) - angle(was[6].points[0]);
    expect(Math.abs(Math.sin(turn))).toBeGreaterThan(0.1);
    turned[6].points.forEach((p, k) => {
      const q = was[6].points[k];
      expect(Math.abs(Math.hypot(p[0] - cursor[0], p[1] - cursor[1]) - Math.hypot(q[0] - cursor[0], q[1] - cursor[1]))).toBeLessThan(ROUNDING);
      expect(Math.abs(p[2] - q[2])).toBeLessThan(ROUNDING);
      expect(Math.abs(Math.sin(angle(p) - angle(q) - turn))).toBeLessThan(ROUNDING);
    });
    turned.forEach((c, i) => i === 6 || expect(c.points).toEqual(was[i].points));

    // The boxes on the cursor: the x box dragged outward (right, in the top view).
    await page.keyboard.press('Shift+g');
    await expect(page.getByTestId('gizmo-mode')).toHaveValue('scale');
    await page.waitForTimeout(200);
    const box = (await page.evaluate(() => (window as any).__studio.gizmoHandle('x'))) as Point;
    const mark = (await page.evaluate(() => (window as any).__studio.cursor())).frame as Point;
    await drag(page, box, { x: box.x + 0.5 * (box.x - mark.x), y: box.y });
    await expect.poll(() => undoDepth(studio)).toBe(2);
    await save(page);
    const scaled = fileJson(studio).curves[6].points as V[];
    const far = turned[6].points.reduce((a, p, k) => (Math.abs(p[0] - cursor[0]) > Math.abs(turned[6].points[a][0] - cursor[0]) ? k : a), 0);
    const factor = (scaled[far][0] - cursor[0]) / (turned[6].points[far][0] - cursor[0]);
    expect(factor).toBeGreaterThan(1.1);
    scaled.forEach((p, k) => {
      const q = turned[6].points[k];
      expect(Math.abs(p[0] - cursor[0] - factor * (q[0] - cursor[0]))).toBeLessThan(ROUNDING);
      expect(Math.abs(p[1] - q[1]) + Math.abs(p[2] - q[2])).toBeLessThan(ROUNDING);
    });
    await undoAll(page, studio, 2);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});
