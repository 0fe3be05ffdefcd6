// The studio's tools as a user works them (issue 17): nothing lost (unknown fields kept,
// unsaved edits asked about, bad numbers refused), export in every format, views and keys,
// analysis (zebra, curvature, boundary curves) and the adaptive preview.
import { readFileSync, existsSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { SOURCE_DIR, dragVertex, expect, meshUpToDate, openStudio, settle, shot, test } from './fixture';

const hooks = (page: Page, name: string, ...args: unknown[]) =>
  page.evaluate(([n, a]) => (window as any).__studio[n as string](...(a as unknown[])), [name, args] as const);

/** Clicks a vertex handle without moving: selects the vertex. */
async function selectVertex(page: Page, vertex: number): Promise<void> {
  const p = await hooks(page, 'vertexScreen', vertex);
  await page.mouse.click(p.x, p.y);
  await expect(page.getByTestId('vertex-index')).toHaveText(`#${vertex}`);
}

test.describe('nothing lost', () => {
  test('Save keeps the description and every field the editor does not show', async ({ page, studio }) => {
    await openStudio(page, studio);
    const original = JSON.parse(readFileSync(path.join(SOURCE_DIR, 'examples', 'sculpt.json'), 'utf8'));
    expect(original.description).toBeTruthy();
    await dragVertex(page, 2, 30, -20, 5);
    await expect(page.getByTestId('dirty')).toBeVisible();
    await page.getByTestId('save').click();
    await expect(page.getByTestId('status')).toContainText('saved sculpt.json');
    const saved = JSON.parse(readFileSync(studio.model, 'utf8'));
    expect(saved.description).toBe(original.description);
    expect(saved.name).toBe(original.name);
    expect(saved.vertices[2]).not.toEqual(original.vertices[2]); // the edit is in it
    expect(saved.vertices[2]).toEqual((await studio.state()).model.vertices[2]);
  });

  test('opening another model with unsaved edits asks: cancel, discard, save', async ({ page, studio }) => {
    await openStudio(page, studio);
    // A second model to open: a copy; then back to the first, edited.
    await page.getByTestId('saveas-path').fill('copy.json');
    await page.getByTestId('save-as').click();
    await expect(page.getByTestId('model-path')).toHaveText('copy.json');
    await page.getByTestId('file-select').selectOption('sculpt.json');
    await page.getByTestId('open').click();
    await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
    await dragVertex(page, 2, 30, -20, 5);
    const edited = (await studio.state()).model.vertices[2];
    await expect(page.getByTestId('dirty')).toBeVisible();

    // Cancel: nothing happens, the edits stay.
    await page.getByTestId('file-select').selectOption('copy.json');
    await page.getByTestId('open').click();
    await expect(page.getByTestId('unsaved-dialog')).toBeVisible();
    await expect(page.getByTestId('unsaved-path')).toHaveText('sculpt.json');
    await page.screenshot({ path: shot('unsaved-dialog.png') });
    await page.getByTestId('unsaved-cancel').click();
    await expect(page.getByTestId('unsaved-dialog')).toBeHidden();
    await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
    expect((await studio.state()).model.vertices[2]).toEqual(edited);
    expect((await studio.state()).dirty).toBe(true);
    // The file list names the model still open, not the one cancelled.
    await expect(page.getByTestId('file-select')).toHaveValue('sculpt.json');

    // Save: the edits are written, then the other model opens.
    await page.getByTestId('file-select').selectOption('copy.json');
    await page.getByTestId('open').click();
    await page.getByTestId('unsaved-save').click();
    await expect(page.getByTestId('model-path')).toHaveText('copy.json');
    expect(JSON.parse(readFileSync(studio.model, 'utf8')).vertices[2]).toEqual(edited);

    // Discard: the other model opens; the edits wait in the autosave, offered on reopening.
    await dragVertex(page, 3, -25, 15, 5);
    await page.getByTestId('file-select').selectOption('sculpt.json');
    await page.getByTestId('open').click();
    await page.getByTestId('unsaved-discard').click();
    await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
    await page.getByTestId('file-select').selectOption('copy.json');
    await page.getByTestId('open').click();
    await expect(page.getByTestId('recovery')).toBeVisible();
  });

  test('an empty box, a lone "-" or text is refused in place and records nothing', async ({ page, studio }) => {
    await openStudio(page, studio);
    await selectVertex(page, 2);
    const before = await studio.state();
    const x = page.getByTestId('vertex-x');
    for (const typed of ['', '-', '1e']) {
      await x.click();
      await x.press('Control+a');
      await x.press('Delete');
      if (typed) await page.keyboard.type(typed);
      await x.press('Enter');
      await expect(x).toHaveClass(/invalid/);
      await expect(page.getByTestId('error')).toContainText(/x: /);
      const now = await studio.state();
      expect(now.model.vertices[2]).toEqual(before.model.vertices[2]);
      expect(now.undo).toBe(before.undo);
      expect(now.revision).toBe(before.revision);
    }
    // A number is taken, and the mark goes.
    await x.fill('0.25');
    await x.press('Enter');
    await settle(page);
    await expect(x).not.toHaveClass(/invalid/);
    expect((await studio.state()).model.vertices[2][0]).toBe(0.25);
    expect((await studio.state()).undo).toBe(before.undo + 1);
    // A magnification box: empty is refused, the slider's value stays.
    await page.mouse.click(...(await frameClick(page, 0)));
    const mag = page.getByTestId('a1-x-mag');
    const value = await page.getByTestId('a1-x-value').inputValue();
    await mag.fill('');
    await mag.press('Enter');
    await expect(mag).toHaveClass(/invalid/);
    await expect(page.getByTestId('a1-x-value')).toHaveValue(value);
    expect((await studio.state()).undo).toBe(before.undo + 1);
  });
});

async function frameClick(page: Page, frame: number): Promise<[number, number]> {
  const p = await hooks(page, 'frameScreen', frame);
  return [p.x, p.y];
}

test('export to every format; the name follows the model, also after Save as', async ({ page, studio }) => {
  await openStudio(page, studio);
  await expect(page.getByTestId('export-name')).toHaveValue('sculpt');
  for (const ext of ['obj', 'stl', 'glb', 'ply', 'off', 'step', 'iges']) {
    await page.getByTestId(`export-${ext}`).click();
    await expect(page.getByTestId('status')).toContainText(`exported sculpt.${ext}`);
    expect(existsSync(path.join(studio.root, `sculpt.${ext}`))).toBe(true);
  }
  expect(readFileSync(path.join(studio.root, 'sculpt.step'), 'utf8').startsWith('ISO-10303-21;')).toBe(true);
  await expect(page.getByTestId('status')).toContainText(/face/);
  await page.getByTestId('saveas-path').fill('renamed');
  await page.getByTestId('save-as').click();
  await expect(page.getByTestId('model-path')).toHaveText('renamed.json');
  await expect(page.getByTestId('export-name')).toHaveValue('renamed');
  await page.getByTestId('export-step').click();
  await expect(page.getByTestId('status')).toContainText('exported renamed.step');
  expect(existsSync(path.join(studio.root, 'renamed.step'))).toBe(true);
});

const close = (a: number[], b: number[], tol = 1e-3) => a.every((x, i) => Math.abs(x - b[i]) < tol);

test('views: presets by key and button, fit selection, linked cameras; help lists the keys', async ({ page, studio }) => {
  await openStudio(page, studio);
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('1');
  let cams = await hooks(page, 'cameras');
  expect(close(cams.frame.direction, [0, -1, 0])).toBe(true);
  expect(close(cams.surface.direction, [0, -1, 0])).toBe(true);
  await page.keyboard.press('5');
  expect(close((await hooks(page, 'cameras')).surface.direction, [0, 0, 1])).toBe(true);
  await page.getByTestId('view-right').click();
  expect(close((await hooks(page, 'cameras')).frame.direction, [1, 0, 0])).toBe(true);
  await page.keyboard.press('0');
  await page.waitForTimeout(300);
  await page.screenshot({ path: shot('views-iso.png') });

  // F fits the selected vertex's frames: the target moves to their box's centre.
  await selectVertex(page, 2);
  await page.locator('body').click({ position: { x: 5, y: 5 } }); // clears nothing: outside the views
  const model = (await studio.state()).model;
  const box = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };
  for (const v of model.frames[0].vertices)
    for (let c = 0; c < 3; ++c) {
      box.min[c] = Math.min(box.min[c], model.vertices[v][c]);
      box.max[c] = Math.max(box.max[c], model.vertices[v][c]);
    }
  await page.keyboard.press('f');
  cams = await hooks(page, 'cameras');
  expect(close(cams.frame.target, [0, 1, 2].map((c) => (box.min[c] + box.max[c]) / 2))).toBe(true);

  // Linked: orbiting the surface view moves the frame view's camera the same way.
  await page.keyboard.press('k');
  await expect(page.getByTestId('link-cameras')).toBeChecked();
  const s = await page.getByTestId('surface-view').boundingBox();
  await page.mouse.move(s!.x + s!.width * 0.3, s!.y + s!.height * 0.3);
  await page.mouse.down();
  await page.mouse.move(s!.x + s!.width * 0.5, s!.y + s!.height * 0.4, { steps: 8 });
  await page.mouse.up();
  // The frame view follows once damping has settled (a frame later on a loaded machine).
  await expect
    .poll(async () => {
      cams = await hooks(page, 'cameras');
      return close(cams.frame.position, cams.surface.position, 1e-6);
    })
    .toBe(true);
  expect(close(cams.frame.direction, [0.55, -1.2, 0.9].map((x) => x / Math.hypot(0.55, 1.2, 0.9)), 1e-2)).toBe(false);

  // ? shows the help with every shortcut; Escape closes it.
  await page.keyboard.press('?');
  await expect(page.getByTestId('help')).toBeVisible();
  for (const key of ['Ctrl+Z', 'Ctrl+S', 'Escape', 'Delete', 'Shift+Delete', 'F', '1', '5', 'K', 'Z', 'C', '?'])
    await expect(page.getByTestId('help-keys').locator('kbd', { hasText: new RegExp(`^${key.replace(/[+?]/g, '\\$&')}$`) })).toHaveCount(1);
  await page.screenshot({ path: shot('help.png') });
  // The user guide's table (docs/studio.md) lists every key the help lists.
  const guide = readFileSync(path.join(SOURCE_DIR, 'docs', 'studio.md'), 'utf8');
  const table = guide.slice(guide.indexOf('## Keyboard shortcuts'));
  for (const key of await page.getByTestId('help-keys').locator('kbd').allTextContents())
    expect(table, `docs/studio.md lacks ${key}`).toMatch(new RegExp(`[|,] ${key.replace(/[+?]/g, '\\$&')}[ ,]`));
  await page.keyboard.press('Escape');
  await expect(page.getByTestId('help')).toBeHidden();
  // Escape again clears the selection.
  await page.keyboard.press('Escape');
  await expect(page.getByTestId('vertex-index')).toHaveText('none');
});

test('Shift+Delete removes the selected force (one undo step), not the frame', async ({ page, studio }) => {
  await openStudio(page, studio);
  await page.mouse.click(...(await frameClick(page, 0)));
  await expect(page.getByTestId('force-1')).toBeVisible();
  await page.getByTestId('force-1').click();
  const before = await studio.state();
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('Shift+Delete');
  await expect.poll(async () => (await studio.state()).model.frames[0].forces.length).toBe(before.model.frames[0].forces.length - 1);
  expect((await studio.state()).model.frames).toHaveLength(before.model.frames.length);
  expect((await studio.state()).model.frames[0].forces[0]).toEqual(before.model.frames[0].forces[0]);
  expect((await studio.state()).undo).toBe(before.undo + 1);
});

test.describe('analysis on the mug', () => {
  test.use({ example: 'mug.json' });

  test('zebra density and direction, curvature with its legend, boundary curves on the surface', async ({ page, studio }) => {
    await openStudio(page, studio);
    await page.getByTestId('zebra').check();
    await expect(page.getByTestId('zebra-options')).toBeVisible();
    await page.getByTestId('zebra-density').fill('40');
    await page.getByTestId('zebra-direction').selectOption('x');
    let a = await hooks(page, 'analysis');
    expect(a).toMatchObject({ material: 'zebra', stripes: 40, axis: [1, 0, 0] });
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('zebra-mug.png') });
    await expect(page.getByTestId('zebra-density-value')).toHaveValue('40');
    // The box beside the slider takes the number exactly, an expression too.
    await page.getByTestId('zebra-density-value').fill('3*8.5');
    await page.getByTestId('zebra-density-value').press('Enter');
    await expect.poll(async () => (await hooks(page, 'analysis')).stripes).toBe(25.5);
    await page.getByTestId('zebra-density-value').fill('100');
    await page.getByTestId('zebra-density-value').press('Enter');
    await expect(page.getByTestId('zebra-density-value')).toHaveClass(/invalid/);
    expect((await hooks(page, 'analysis')).stripes).toBe(25.5); // refused in place

    await page.getByTestId('curvature').selectOption('mean');
    // From the analytic surface (GET /api/curvature), not the mesh estimate.
    await expect.poll(async () => (await hooks(page, 'analysis')).analyticCurvature).toBe(true);
    a = await hooks(page, 'analysis');
    expect(a.material).toBe('curvature');
    expect(a.curvatureRange).toBeGreaterThan(0);
    await expect(page.getByTestId('zebra')).not.toBeChecked();
    await expect(page.getByTestId('curvature-legend')).toBeVisible();
    await expect(page.getByTestId('legend-title')).toContainText('mean curvature');
    await expect(page.getByTestId('legend-max')).toContainText(/≥ \d/);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('curvature-mean-mug.png') });
    await page.locator('body').click({ position: { x: 5, y: 5 } });
    await page.keyboard.press('c'); // mean -> Gaussian
    await expect(page.getByTestId('legend-title')).toContainText('Gaussian');
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('curvature-gaussian-mug.png') });

    // The frame overlay: the patches' true boundary curves, which run along the surface's
    // mesh (every overlay point is a vertex of the surface, to float rounding).
    await expect.poll(async () => (await hooks(page, 'overlayPoints')).length).toBeGreaterThan(0);
    const points: number[] = await hooks(page, 'overlayPoints');
    const mesh: number[] = await hooks(page, 'meshPositions');
    const keys = new Set<string>();
    const q = (x: number) => Math.round(x * 1e4);
    for (let i = 0; i < mesh.length; i += 3) keys.add(`${q(mesh[i])},${q(mesh[i + 1])},${q(mesh[i + 2])}`);
    let on = 0;
    for (let i = 0; i < points.length; i += 3) if (keys.has(`${q(points[i])},${q(points[i + 1])},${q(points[i + 2])}`)) ++on;
    expect(on / (points.length / 3)).toBeGreaterThan(0.95); // rounding to 1e-4 may split a few
    expect(points.length / 3).toBe(62 * 4 * (24 - 1) * 2);
  });

  test('a drag redraws the frame view only around the moved handle, the pixels of a whole draw', async ({ page, studio }) => {
    await openStudio(page, studio);
    const regions = await hooks(page, 'frameRegionDraws');
    const p = await hooks(page, 'vertexScreen', 40);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    for (let i = 1; i <= 6; ++i) {
      await page.mouse.move(p.x + 5 * i, p.y - 3 * i);
      await settle(page);
      // Drawn in the next frame; then compared with a whole draw of the same state.
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      const { differ, pixels } = await hooks(page, 'frameRedrawDifference');
      expect(pixels).toBeGreaterThan(100_000);
      expect(differ).toBe(0);
    }
    await page.mouse.up();
    await settle(page);
    expect(await hooks(page, 'frameRegionDraws')).toBeGreaterThan(regions);
  });

  test('a drag shows a coarser preview and returns to full resolution on release', async ({ page, studio }) => {
    await openStudio(page, studio);
    expect((await hooks(page, 'state')).resolution).toBe(24);
    const p = await hooks(page, 'vertexScreen', 40);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    const seen = new Set<number>();
    for (let i = 1; i <= 6; ++i) {
      await page.mouse.move(p.x + 3 * i, p.y - 4 * i);
      await settle(page);
      await meshUpToDate(page);
      seen.add((await hooks(page, 'state')).resolution);
    }
    expect(Math.max(...seen)).toBeLessThan(24);
    // The release: a delta against the last Res 24 mesh the page kept (apps/studio/README.md).
    const deltas = (await hooks(page, 'state')).meshDeltas;
    await page.mouse.up();
    await expect.poll(async () => (await hooks(page, 'state')).resolution).toBe(24);
    await meshUpToDate(page);
    expect((await hooks(page, 'state')).meshDeltas).toBeGreaterThan(deltas);
    expect(await hooks(page, 'meshMatchesServer')).toBe(true);
  });

  test('after a previewed drag the surface view draws what a reload draws, pixel for pixel', async ({ page, studio }) => {
    await openStudio(page, studio);
    const p = await hooks(page, 'vertexScreen', 40);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    for (let i = 1; i <= 4; ++i) {
      await page.mouse.move(p.x + 3 * i, p.y - 4 * i);
      await settle(page);
      await meshUpToDate(page);
    }
    // The preview: a coarser mesh, drawn into a quarter of the canvas shown twice as large.
    expect((await hooks(page, 'state')).resolution).toBeLessThan(24);
    expect((await hooks(page, 'surfacePixels')).transform).toBe('scale(2)');
    await page.mouse.up();
    await settle(page);
    await expect.poll(async () => (await hooks(page, 'state')).resolution).toBe(24);
    await meshUpToDate(page);
    // The release's mesh came as a delta written into the kept Res 24 buffers, and the
    // boundary curves came after it.
    await expect.poll(async () => (await hooks(page, 'draws')).overlay).toBe(true);
    const camera = (await hooks(page, 'cameras')).surface;
    const released = await hooks(page, 'surfacePixels');
    expect(released.transform).toBe('');

    // A reload makes every buffer afresh from whole meshes; the same camera.
    await page.reload();
    await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
    await meshUpToDate(page);
    await expect.poll(async () => (await hooks(page, 'draws')).overlay).toBe(true);
    await selectVertex(page, 40); // its dot on the surface, as after the drag
    await hooks(page, 'setSurfaceCamera', camera);
    const fresh = await hooks(page, 'surfacePixels');
    expect([fresh.width, fresh.height]).toEqual([released.width, released.height]);
    const a = Buffer.from(released.base64, 'base64'), b = Buffer.from(fresh.base64, 'base64');
    let differ = 0, surface = 0;
    for (let i = 0; i < a.length; i += 4) {
      if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) ++differ;
      if (Math.abs(a[i] - 0xf4) + Math.abs(a[i + 1] - 0xf5) + Math.abs(a[i + 2] - 0xf7) > 30) ++surface; // not the clear colour
    }
    expect(surface).toBeGreaterThan(50_000); // the mug covers a good part of the view
    expect(differ).toBe(0);
  });
});
