// The shape editor, as a user does it: a point drag on the shell refused (told before), a
// spectral model's spine point dragged, its operator changed, a section's point dragged (the
// section bends round it) and a section added and removed, a net's control point and a
// boundary curve's point dragged; save and read the file's numbers; undo and save: the file
// byte for byte as it was. The spine drag gives the spine `pdesurf spine` reads from the file.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { CLI, expect, meshUpToDate, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** The solves meet their moved points to rounding (kThrough in
 * tests/session/shape_edits_test.cpp); the file writes numbers shortest round-trip. */
const THROUGH = 1e-9;

type Handle = { kind: string; curve?: number | string; point?: number; i?: number; j?: number; index?: number; p: number[]; x: number; y: number; visible: boolean };

const handles = (page: Page): Promise<Handle[]> => page.evaluate(() => (window as any).__shape.handles());
const fileText = (studio: Studio) => readFileSync(studio.model, 'utf8');
const fileJson = (studio: Studio) => JSON.parse(fileText(studio));

/** Drags the first visible handle that `which` accepts by (dx, dy) pixels; its handle. The
 * model's drawing may move under a loaded machine's first frames: retried until the page
 * reports a gesture's edit. */
async function dragHandle(page: Page, which: (h: Handle) => boolean, dx: number, dy: number): Promise<Handle> {
  const list = (await handles(page)).filter((h) => h.visible && which(h));
  expect(list.length).toBeGreaterThan(0);
  const h = list[Math.floor(list.length / 2)];
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.mouse.move(h.x + dx, h.y + dy, { steps: 6 });
  await page.mouse.up();
  await settle(page);
  return h;
}

async function save(page: Page): Promise<void> {
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
}

/** Ctrl+Z, then waits until the server has undone (a save sent sooner could overtake it). */
async function undo(page: Page, studio: Studio): Promise<void> {
  await expect(page.getByTestId('undo')).toBeEnabled();
  const before = (await studio.state()).undo;
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await studio.state()).undo).toBe(before - 1);
}

const distance = (a: number[], b: number[]) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

// These tests do a user's many steps in software WebGL: more time than the default 60 s.
test.describe.configure({ timeout: 240_000 });

test.describe('a spectral model of points (the shell)', () => {
  test.use({ example: 'shell.json' });

  test('told before a point drag; a drag that would throw the surface away is refused, the file unchanged', async ({ page, studio }) => {
    const original = fileText(studio);
    await openStudio(page, studio);
    await expect(page.getByTestId('shape-tools')).toBeVisible();
    // Order 12 through 12 curves: said before the drag, with what to do instead.
    await expect(page.getByTestId('drag-advice-text')).toContainText('ill-conditioned');
    await expect(page.getByTestId('use-global-chain')).toBeHidden();
    await dragHandle(page, (x) => x.kind === 'curve' && x.curve === 5, 40, -30);
    await expect(page.getByTestId('error')).toContainText('would move the surface');
    await page.screenshot({ path: shot('shape-curve-point-refused.png') });
    expect((await studio.state()).undo).toBe(0);
    expect((await studio.state()).dirty).toBe(false);
    await save(page);
    expect(fileText(studio)).toBe(original);
  });
});

test.describe('a spectral model of Fourier curves (the membrane)', () => {
  test.use({ example: 'membrane.json' });

  test('drag a spine point: the file\'s spine, `pdesurf spine` and the page agree; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    await openStudio(page, studio);
    const spine = (await handles(page)).filter((h) => h.kind === 'spine');
    expect(spine).toHaveLength(9);
    const h = await dragHandle(page, (x) => x.kind === 'spine' && x.index === 4, 50, 0);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-spine.png') });
    await save(page);
    const edits = fileJson(studio).spine;
    expect(edits).toHaveLength(1);
    expect(edits[0].u).toHaveLength(9);
    // The other spine points held where they were; the dragged one moved.
    edits[0].moved.forEach((p: number[], k: number) =>
      k === h.index ? expect(distance(p, h.p)).toBeGreaterThan(1e-3) : expect(distance(p, spine[k].p)).toBeLessThan(THROUGH),
    );
    // `pdesurf spine` of the saved file passes through the file's points, at the file's u.
    const cli = JSON.parse(execFileSync(CLI, ['spine', studio.model, '--count', '9'], { encoding: 'utf8' })).patches[0];
    expect(cli.u).toEqual(edits[0].u);
    cli.points.forEach((p: number[], k: number) => expect(distance(p, edits[0].moved[k])).toBeLessThan(THROUGH));
    // ... and the page's spine handles are those points.
    const after = (await handles(page)).filter((x) => x.kind === 'spine');
    after.forEach((x, k) => expect(distance(x.p, cli.points[k])).toBeLessThan(THROUGH));
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);
  });

  test('operator: a typed a and the slider take effect, N that needs other conditions is refused', async ({ page, studio }) => {
    const original = fileText(studio);
    await openStudio(page, studio);
    await expect(page.getByTestId('operator-tools')).toBeVisible();
    // The panel shows the file's operator (as the server's settings say it).
    const file = JSON.parse(original);
    await expect(page.getByTestId('operator-kind')).toHaveValue(file.operator);
    await expect(page.getByTestId('operator-n')).toHaveValue(String(file.N));
    await expect(page.getByTestId('operator-a')).toHaveValue(String(file.a));
    await expect(page.getByTestId('operator-modes')).toHaveValue(String(file.modes));
    await expect(page.getByTestId('operator-remainder')).toBeChecked({ checked: file.remainder });
    await expect(page.getByTestId('section-tools')).toBeHidden();
    await page.getByTestId('operator-a').fill('2.5');
    await page.getByTestId('operator-a').press('Enter');
    await expect.poll(async () => (await studio.state()).model.a).toBe(2.5);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-operator.png') });
    // N = 5 is order 10: the membrane has 8 conditions.
    await page.getByTestId('operator-n').fill('5');
    await page.getByTestId('operator-n').press('Enter');
    await expect(page.getByTestId('error')).toContainText('10');
    expect((await studio.state()).model.N).toBe(4);
    await expect(page.getByTestId('operator-n')).toHaveValue('4'); // the model's again
    // The slider: a gesture of several edits, one undo step.
    const slider = page.getByTestId('operator-a-slider');
    const box = (await slider.boundingBox())!;
    await page.mouse.move(box.x + box.width * 0.3, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height / 2, { steps: 5 });
    await page.mouse.up();
    await settle(page);
    await expect.poll(async () => (await studio.state()).model.a).not.toBe(2.5);
    await undo(page, studio);
    await expect.poll(async () => (await studio.state()).model.a).toBe(2.5);
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a cross-section chain (the vase)', () => {
  test.use({ example: 'vase-sections.json' });

  test('add a section after the chosen one, remove it, turn one; each undone', async ({ page, studio }) => {
    const original = fileText(studio);
    const count = JSON.parse(original).curves.length;
    await openStudio(page, studio);
    // A chain's operator: a, modes and the remainder; no kind or N.
    await expect(page.getByTestId('section-tools')).toBeVisible();
    await expect(page.getByTestId('operator-a')).toHaveValue(String(JSON.parse(original).a));
    await expect(page.getByTestId('operator-n-label')).toBeHidden();
    await expect(page.getByTestId('operator-kind-label')).toBeHidden();
    // A point of the top section dragged: the chain passes through it.
    const h = await dragHandle(page, (x) => x.kind === 'curve' && x.curve === count - 1, 25, -15);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-section-point.png') });
    await save(page);
    const top = fileJson(studio).curves[count - 1].points;
    expect(distance(top[h.point!], h.p)).toBeGreaterThan(1e-3);
    // The section bent round the point (the page's falloff, an eighth of the way round each
    // side): its neighbours followed, the far side did not move.
    const topWas = JSON.parse(original).curves[count - 1].points;
    const n = topWas.length;
    const apart = (k: number) => Math.min(Math.abs(k - h.point!), n - Math.abs(k - h.point!));
    for (let k = 0; k < n; ++k) if (apart(k) > n / 4) expect(top[k]).toEqual(topWas[k]);
    expect(distance(top[(h.point! + 1) % n], topWas[(h.point! + 1) % n])).toBeGreaterThan(1e-4);
    await undo(page, studio);
    await page.getByTestId('curve-select').selectOption('5');
    await page.getByTestId('add-section').click();
    await expect.poll(async () => (await studio.state()).model.curves.length).toBe(count + 1);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-section.png') });
    await save(page);
    const added = fileJson(studio).curves[6];
    expect(added.points.length).toBeGreaterThanOrEqual(16);
    await page.getByTestId('curve-select').selectOption('6');
    await page.getByTestId('remove-section').click();
    await expect.poll(async () => (await studio.state()).model.curves.length).toBe(count);
    await undo(page, studio);
    await undo(page, studio);
    await expect.poll(async () => (await studio.state()).model.curves.length).toBe(count);
    // A section scaled about its centre.
    await page.getByTestId('curve-select').selectOption('0');
    await page.getByTestId('curve-scale-factor').fill('1.5');
    await page.getByTestId('curve-scale').click();
    await expect.poll(async () => (await studio.state()).undo).toBeGreaterThan(0);
    await save(page);
    const was = JSON.parse(original).curves[0].points;
    const now = fileJson(studio).curves[0].points;
    const centre = [0, 1, 2].map((c) => was.reduce((s: number, p: number[]) => s + p[c], 0) / was.length);
    now.forEach((p: number[], k: number) =>
      expect(distance(p, [0, 1, 2].map((c) => centre[c] + 1.5 * (was[k][c] - centre[c])))).toBeLessThan(THROUGH),
    );
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a B-spline PDE net (the wave)', () => {
  test.use({ example: 'bspline-wave.json' });

  test('drag a given control point: the inner points are solved again; undo; the gizmo\'s ring turns a picked one about the 3D cursor', async ({ page, studio }) => {
    const original = fileText(studio);
    await openStudio(page, studio);
    const before = (await studio.state()).view.curves;
    const h = await dragHandle(page, (x) => x.kind === 'control' && x.i === 0, 0, -40);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-net.png') });
    await save(page);
    const net = fileJson(studio).net;
    expect(distance(net[h.i!][h.j!], h.p)).toBeGreaterThan(1e-3);
    // The control polygons the page draws (given and solved points) changed inside too.
    const after = (await studio.state()).view.curves;
    const inner = (c: number[][][]) => c.flatMap((line) => line.slice(2, -2)).flat();
    expect(inner(after)).not.toEqual(inner(before));
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);

    // The point picked (a click), the 3D cursor a quarter to its side as the pivot: the
    // gizmo's z ring turns the point alone about the cursor (one undo step).
    await page.getByTestId('view-top').click();
    await page.waitForTimeout(400);
    const picked = (await handles(page)).find((x) => x.kind === 'control' && x.i === h.i && x.j === h.j)!;
    await page.mouse.click(picked.x, picked.y);
    await expect(page.getByTestId('shape-handle')).toHaveText(`P[${h.i}][${h.j}]`);
    await page.getByTestId('cursor-to-selection').click();
    const x = await page.getByTestId('cursor-x').inputValue();
    await page.getByTestId('cursor-x').fill(`${x} + 1/4`);
    await page.getByTestId('cursor-x').press('Enter');
    await expect.poll(() => page.getByTestId('cursor-x').inputValue()).not.toBe(x);
    const cursor = (await page.evaluate(() => (window as any).__studio.cursor())).p as number[];
    await page.getByTestId('selection-pivot').selectOption('cursor');
    await page.locator('body').click({ position: { x: 5, y: 5 } });
    await page.keyboard.press('g');
    await page.keyboard.press('Shift+g');
    await expect(page.getByTestId('gizmo-mode')).toHaveValue('rotate');
    await page.waitForTimeout(200);
    const ring = (angle: number) => page.evaluate((a) => (window as any).__studio.gizmoHandle('z', a), angle) as Promise<{ x: number; y: number }>;
    const [from, to] = [await ring(Math.PI / 4), await ring(Math.PI / 4 + 0.8)];
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(to.x, to.y, { steps: 8 });
    await page.mouse.up();
    await settle(page);
    await expect.poll(async () => (await studio.state()).undo).toBe(1);
    await save(page);
    const was = JSON.parse(original).net, now = fileJson(studio).net;
    const p = now[h.i!][h.j!], q = was[h.i!][h.j!];
    const flat = (a: number[]) => Math.hypot(a[0] - cursor[0], a[1] - cursor[1]);
    expect(distance(p, q)).toBeGreaterThan(0.05);
    expect(Math.abs(flat(p) - flat(q))).toBeLessThan(THROUGH);
    expect(Math.abs(p[2] - q[2])).toBeLessThan(THROUGH);
    was.forEach((row: (number[] | null)[], i: number) =>
      row.forEach((c, j) => (i <= 1 || i === was.length - 1 || j <= 1 || j === row.length - 1) && (i !== h.i || j !== h.j) && expect(now[i][j]).toEqual(c)),
    );
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});

test.describe('a B-spline PDE boundary (the dome)', () => {
  test.use({ example: 'bspline-dome.json' });

  test('drag a boundary curve point; undo', async ({ page, studio }) => {
    const original = fileText(studio);
    await openStudio(page, studio);
    const h = await dragHandle(page, (x) => x.kind === 'curve' && x.curve === 'uMin', 0, -30);
    await meshUpToDate(page);
    await page.screenshot({ path: shot('shape-boundary.png') });
    await save(page);
    const curve = fileJson(studio).boundary.uMin;
    const points = curve.bspline ?? curve.points;
    expect(distance(points[h.point!], h.p)).toBeGreaterThan(1e-3);
    await undo(page, studio);
    await save(page);
    await expect.poll(() => fileText(studio)).toBe(original);
  });
});
