// The modeller's moving tools and forces on the surface, as a user does them: the move gizmo's
// arrow dragged, the selection scaled and turned with keys, vertices box-selected in the
// surface view (never one hidden behind the surface), a force region drawn as a rectangle on
// a patch and resized by its handle; the saved file's numbers checked, and every step undone
// byte for byte.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { expect, newModel, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** A region bound picked with the mouse is within this of where it was aimed: a pixel is
 * about 1/500 of the patch in these views, and the aim is rounded to whole pixels. */
const PICK_UV = 0.01;
/** A coordinate the studio computes from typed numbers (a scale, a quarter turn) is exact to
 * rounding. */
const ROUNDING = 1e-9;

type Point = { x: number; y: number };
const hook = <T>(page: Page, name: string, ...args: unknown[]) =>
  page.evaluate(([n, a]) => (window as any).__studio[n as string](...(a as unknown[])), [name, args] as const) as Promise<T>;

const fileText = (studio: Studio, name: string) => readFileSync(path.join(studio.root, name), 'utf8');
const model = async (studio: Studio) => (await studio.state()).model;

/** Selects frame `f` by clicking its patch on the surface (again until it is selected: a
 * click can be lost while software WebGL renders). */
async function pickPatch(page: Page, f: number): Promise<void> {
  await expect(async () => {
    const p = await hook<Point>(page, 'patchScreen', f);
    await page.mouse.click(p.x, p.y);
    expect((await hook<{ frames: number[] }>(page, 'selection')).frames).toEqual([f]);
  }).toPass({ timeout: 30000 });
}

async function drag(page: Page, from: Point, to: Point, shift = false): Promise<void> {
  await page.mouse.move(from.x, from.y);
  if (shift) await page.keyboard.down('Shift');
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps: 8 });
  await page.mouse.up();
  if (shift) await page.keyboard.up('Shift');
  await settle(page);
}

/** Ctrl+Z once the page's Undo is enabled, then saved: the file is `expected` again. */
async function undoTo(page: Page, studio: Studio, file: string, expected: string, times = 1): Promise<void> {
  for (let i = 0; i < times; ++i) {
    await expect(page.getByTestId('undo')).toBeEnabled();
    const depth = (await studio.state()).undo;
    await page.keyboard.press('Control+z');
    await expect.poll(async () => (await studio.state()).undo).toBe(depth - 1);
  }
  await page.keyboard.press('Control+s');
  await expect.poll(() => fileText(studio, file)).toBe(expected);
}

// Many user steps in software WebGL: more time than the default 60 s.
test.describe.configure({ timeout: 240_000 });

test('the gizmo arrow moves the selection along x; Shift+S scales and Shift+R turns it about its centre', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'move.json', 2, 1);
  await page.keyboard.press('Control+s');
  const original = fileText(studio, 'move.json');
  const m = await model(studio);
  const frame1 = [...new Set<number>(m.frames[1].vertices)].sort((a, b) => a - b);
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await pickPatch(page, 1);
  await page.keyboard.press('g');
  await expect(page.getByTestId('gizmo')).toBeChecked();

  // Top view: x runs to the right on screen. The arrow dragged 80 px right.
  const arrow = await hook<Point>(page, 'gizmoArrow', 'x');
  expect(arrow).not.toBeNull();
  await page.waitForTimeout(200);
  await drag(page, arrow, { x: arrow.x + 80, y: arrow.y + 30 }); // off the axis: only x counts
  const moved = await model(studio);
  const dx = moved.vertices[frame1[0]][0] - m.vertices[frame1[0]][0];
  expect(dx).toBeGreaterThan(0.05);
  for (const v of frame1) {
    expect(moved.vertices[v][0] - m.vertices[v][0]).toBeCloseTo(dx, 9);
    expect(moved.vertices[v][1]).toBeCloseTo(m.vertices[v][1], 9);
    expect(moved.vertices[v][2]).toBeCloseTo(m.vertices[v][2], 9);
  }
  m.vertices.forEach((p: number[], v: number) => frame1.includes(v) || expect(moved.vertices[v]).toEqual(p));
  expect((await studio.state()).undo).toBe(1); // one drag, one undo step
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('modeller-gizmo.png') });
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  expect(JSON.parse(fileText(studio, 'move.json')).vertices[frame1[0]][0]).toBeCloseTo(m.vertices[frame1[0]][0] + dx, 12);
  await undoTo(page, studio, 'move.json', original);

  // Shift+S: the frame's vertices 2 times as far from their centre, the others unmoved.
  await page.keyboard.press('g');
  await page.getByTestId('selection-scale').fill('2');
  await page.locator('body').click({ position: { x: 5, y: 5 } }); // leave the box: keys are keys again
  await pickPatch(page, 1);
  await page.keyboard.press('Shift+S');
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  const scaled = await model(studio);
  const centre = [0, 1, 2].map((c) => {
    const xs = frame1.map((v) => m.vertices[v][c]);
    return (Math.min(...xs) + Math.max(...xs)) / 2;
  });
  for (const v of frame1)
    for (let c = 0; c < 3; ++c)
      expect(Math.abs(scaled.vertices[v][c] - (centre[c] + 2 * (m.vertices[v][c] - centre[c])))).toBeLessThan(ROUNDING);
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('modeller-scale.png') });
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await undoTo(page, studio, 'move.json', original);

  // Shift+R: a quarter turn about z through the centre: (x, y) → (cx − (y − cy), cy + (x − cx)).
  await page.getByTestId('selection-degrees').fill('90');
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await pickPatch(page, 1);
  await page.keyboard.press('Shift+R');
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  const turned = await model(studio);
  for (const v of frame1) {
    const [x, y, z] = m.vertices[v];
    expect(Math.abs(turned.vertices[v][0] - (centre[0] - (y - centre[1])))).toBeLessThan(ROUNDING);
    expect(Math.abs(turned.vertices[v][1] - (centre[1] + (x - centre[0])))).toBeLessThan(ROUNDING);
    expect(turned.vertices[v][2]).toBe(z);
  }
  await undoTo(page, studio, 'move.json', original);
});

/** A new tube of 6 frames seen from the front (the camera looks along +y, so the back of
 * the tube, y > 0, is behind its front): its front and back vertices. */
async function tubeFromTheFront(page: Page, studio: Studio): Promise<{ front: number[]; back: number[] }> {
  await openStudio(page, studio);
  await newModel(page, 'tube', 'tube.json', 6, 1);
  const m = await model(studio);
  const radius = Math.max(...m.vertices.map((p: number[]) => Math.hypot(p[0], p[1])));
  await page.getByTestId('view-front').click();
  await page.waitForTimeout(400);
  const indices: number[] = m.vertices.map((_: unknown, i: number) => i);
  return {
    front: indices.filter((i) => m.vertices[i][1] < -0.5 * radius),
    back: indices.filter((i) => m.vertices[i][1] > 0.5 * radius),
  };
}

test('a box in the surface view selects the vertices seen, none hidden behind the surface', async ({ page, studio }) => {
  const { front, back } = await tubeFromTheFront(page, studio);
  const box = (await page.getByTestId('surface-view').boundingBox())!;
  await drag(page, { x: box.x + 8, y: box.y + 40 }, { x: box.x + box.width - 8, y: box.y + box.height - 8 }, true);
  const picked: number[] = (await hook<{ vertices: number[] }>(page, 'selection')).vertices;
  expect(front.length).toBeGreaterThan(0);
  expect(back.length).toBeGreaterThan(0);
  for (const v of front) expect(picked).toContain(v);
  for (const v of back) expect(picked).not.toContain(v);
  await page.screenshot({ path: shot('modeller-surface-box.png') });
});

test('a click on a vertex seen in the surface view selects it; a vertex behind the surface is never picked', async ({ page, studio }) => {
  const { front, back } = await tubeFromTheFront(page, studio);
  const screen = async (v: number) => (await hook<Point & { visible: boolean }>(page, 'vertexSurfaceScreen', v))!;
  const selected = async () => (await hook<{ vertices: number[] }>(page, 'selection')).vertices;

  const [a, b] = front;
  const pa = await screen(a);
  await page.mouse.click(pa.x + 2, pa.y - 2); // within the pick radius, not on the dot
  await expect.poll(selected).toEqual([a]);
  const pb = await screen(b);
  await page.keyboard.down('Shift');
  await page.mouse.click(pb.x, pb.y);
  await page.keyboard.up('Shift');
  await expect.poll(selected).toEqual([a, b]);

  // At a back vertex's own screen point (distance 0) a click picks a front one or none:
  // never the vertex the surface hides.
  for (const v of back) {
    const p = await screen(v);
    if (!p.visible) continue;
    await page.mouse.click(p.x, p.y);
    await settle(page);
    expect(await selected()).not.toContain(v);
  }
});

test('draw a force rectangle on a patch, resize it by a handle, edit its numbers; undone byte for byte', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'force.json');
  await page.keyboard.press('Control+s');
  const original = fileText(studio, 'force.json');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await pickPatch(page, 0);

  // D, then a drag from (u, v) = (0.2, 0.3) to (0.6, 0.8) on the patch.
  await page.keyboard.press('d');
  await expect(page.getByTestId('draw-force')).toHaveAttribute('aria-pressed', 'true');
  const a = await hook<Point>(page, 'uvScreen', 0, 0.2, 0.3);
  const b = await hook<Point>(page, 'uvScreen', 0, 0.6, 0.8);
  await drag(page, a, b);
  await expect.poll(async () => (await model(studio)).frames[0].forces?.length ?? 0).toBe(1);
  const region = (await model(studio)).frames[0].forces[0].region;
  [0.2, 0.6, 0.3, 0.8].forEach((x, i) => expect(Math.abs(region[i] - x)).toBeLessThan(PICK_UV));
  // The panel shows the same numbers.
  await expect(page.getByTestId('force-0-u1')).toHaveValue(String(region[1]));
  await page.keyboard.press('d');
  await page.waitForTimeout(300);
  await page.screenshot({ path: shot('modeller-force-draw.png') });

  // The corner handle (u1, v1) dragged to (0.9, 0.95): the opposite corner stays.
  const handle = await hook<Point>(page, 'forceHandle', 2);
  expect(Math.hypot(handle.x - b.x, handle.y - b.y)).toBeLessThan(3);
  await drag(page, handle, await hook<Point>(page, 'uvScreen', 0, 0.9, 0.95));
  await expect.poll(async () => (await model(studio)).frames[0].forces[0].region[1]).not.toBe(region[1]);
  const resized = (await model(studio)).frames[0].forces[0].region;
  expect(resized[0]).toBe(region[0]);
  expect(resized[2]).toBe(region[2]);
  expect(Math.abs(resized[1] - 0.9)).toBeLessThan(PICK_UV);
  expect(Math.abs(resized[3] - 0.95)).toBeLessThan(PICK_UV);

  // The centre handle dragged 0.05 toward u = 0: the region moves whole.
  const mid = [(resized[0] + resized[1]) / 2, (resized[2] + resized[3]) / 2];
  await drag(page, await hook<Point>(page, 'forceHandle', 4), await hook<Point>(page, 'uvScreen', 0, mid[0] - 0.05, mid[1]));
  await expect.poll(async () => (await model(studio)).frames[0].forces[0].region[0]).not.toBe(resized[0]);
  const shifted = (await model(studio)).frames[0].forces[0].region;
  expect(Math.abs(shifted[0] - (resized[0] - 0.05))).toBeLessThan(PICK_UV);
  expect(shifted[1] - shifted[0]).toBeCloseTo(resized[1] - resized[0], 9);
  expect(shifted[3] - shifted[2]).toBeCloseTo(resized[3] - resized[2], 9);
  resized.splice(0, 4, ...shifted);

  // A typed u0: the handle follows it on the surface.
  await page.getByTestId('force-0-u0').fill('0.1');
  await page.getByTestId('force-0-u0').press('Enter');
  await expect.poll(async () => (await model(studio)).frames[0].forces[0].region[0]).toBe(0.1);
  const corner = await hook<Point>(page, 'uvScreen', 0, 0.1, resized[2]);
  await expect
    .poll(async () => {
      const h = await hook<Point>(page, 'forceHandle', 0);
      return Math.hypot(h.x - corner.x, h.y - corner.y);
    })
    .toBeLessThan(2);
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  const saved = JSON.parse(fileText(studio, 'force.json'));
  expect(saved.frames[0].forces).toEqual([{ f0: [0, 0, 0], region: [0.1, resized[1], resized[2], resized[3]] }]);
  await page.screenshot({ path: shot('modeller-force-handles.png') });

  // Four edits (draw, resize, move, typed), four undo steps: the file as it was.
  await undoTo(page, studio, 'force.json', original, 4);
});

test('the selected frame\'s force regions are drawn on its patch, with handles on the selected one', async ({ page, studio }) => {
  await openStudio(page, studio); // sculpt.json: one frame, two forces
  const m = await model(studio);
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await pickPatch(page, 0);
  const regions = m.frames[0].forces.map((f: { region?: number[] }) => f.region ?? [0, 1, 0, 1]);
  await expect.poll(() => hook<{ region: number[] }[]>(page, 'forceOutlines').then((o) => o.map((x) => x.region))).toEqual(regions);
  // The selected force's centre handle is at its region's centre on the surface.
  const r = regions[0];
  const centre = await hook<Point>(page, 'uvScreen', 0, (r[0] + r[1]) / 2, (r[2] + r[3]) / 2);
  const handle = await hook<Point>(page, 'forceHandle', 4);
  expect(Math.hypot(handle.x - centre.x, handle.y - centre.y)).toBeLessThan(1);
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(400);
  await page.screenshot({ path: shot('modeller-force-regions.png') });
});

test.describe('shared forces', () => {
  test.use({ example: 'grid-forces.json' });
  test('a shared force over the selected frame outlines every frame it acts on', async ({ page, studio }) => {
    await openStudio(page, studio);
    const shared = (await model(studio)).forces[0].frames as number[];
    await page.getByTestId('view-iso').click();
    await page.waitForTimeout(300);
    await pickPatch(page, shared[0]);
    await expect
      .poll(() => hook<{ frame: number; region: number[] }[]>(page, 'forceOutlines'))
      .toEqual(shared.map((frame) => ({ frame, region: [0, 1, 0, 1] })));
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('modeller-shared-force.png') });
  });
});
