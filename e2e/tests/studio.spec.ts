import { existsSync, statSync } from 'node:fs';
import path from 'node:path';
import { dragVertex, expect, meshUpToDate, openStudio, pageState, settle, shot, test } from './fixture';

const surface = (page: import('@playwright/test').Page) =>
  page.locator('[data-testid="surface-view"] canvas');

test('the page loads the model and its mesh', async ({ page, studio }) => {
  await openStudio(page, studio);
  await expect(page.getByTestId('status')).toContainText('1 frame');
  await expect(page.getByTestId('status')).toContainText('8 vertices');
  await expect(page.getByTestId('status')).toContainText(/solve [\d.]+ ms/);
  await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
  await expect(page.getByTestId('frame-tools')).toBeVisible();
  await expect(page.getByTestId('error')).toHaveText('');
  await page.screenshot({ path: shot('loaded.png') });
});

test.describe('grid-forces', () => {
  test.use({ example: 'grid-forces.json' });

  test('loads 16 frames; zebra stripes', async ({ page, studio }) => {
    await openStudio(page, studio);
    await expect(page.getByTestId('status')).toContainText('16 frames');
    await page.getByTestId('zebra').check();
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('grid-zebra.png') });
  });
});

test('drag a vertex: the model and the surface change; undo and redo', async ({ page, studio }) => {
  await openStudio(page, studio);
  const before = (await studio.state()).model.vertices[4];
  await page.waitForTimeout(300);
  const imageBefore = await surface(page).screenshot();

  const p = await page.evaluate(() => (window as any).__studio.vertexScreen(4));
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(p.x + 4 * i, p.y - 8 * i);
  await page.mouse.up();
  await settle(page);
  await expect(page.getByTestId('vertex-index')).toHaveText('#4');

  await expect.poll(async () => (await studio.state()).undo).toBe(1); // one drag: one undo step
  const moved = (await studio.state()).model.vertices[4];
  expect(moved).not.toEqual(before);
  await meshUpToDate(page);
  await page.waitForTimeout(300);
  const imageAfter = await surface(page).screenshot();
  expect(imageAfter.equals(imageBefore)).toBe(false);
  await page.screenshot({ path: shot('dragged.png') });
  // The page patched its mesh with deltas during the drag: it is the server's whole mesh.
  expect(await page.evaluate(() => (window as any).__studio.state().meshDeltas)).toBeGreaterThan(0);
  expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);

  // The coordinate inputs show the moved vertex.
  expect(Number(await page.getByTestId('vertex-z').inputValue())).toBeCloseTo(moved[2], 3);

  await page.locator('body').click({ position: { x: 5, y: 5 } });
  // Each key or click once the page shows the step is possible (its button enabled), as a
  // user sees it: the page learns it from the answer to the step before.
  await expect(page.getByTestId('undo')).toBeEnabled();
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await studio.state()).model.vertices[4]).toEqual(before);
  await expect(page.getByTestId('redo')).toBeEnabled();
  await page.keyboard.press('Control+Shift+z');
  await expect.poll(async () => (await studio.state()).model.vertices[4]).toEqual(moved);
  await expect(page.getByTestId('undo')).toBeEnabled();
  await page.getByTestId('undo').click();
  await expect.poll(async () => (await studio.state()).model.vertices[4]).toEqual(before);
  await expect(page.getByTestId('redo')).toBeEnabled();
  await page.getByTestId('redo').click();
  await expect.poll(async () => (await studio.state()).model.vertices[4]).toEqual(moved);
});

test('typing a coordinate moves the selected vertex', async ({ page, studio }) => {
  await openStudio(page, studio);
  // Software WebGL on a loaded machine can drop the first click while a frame renders:
  // click again until the vertex is selected (the selection itself is what is asserted).
  await expect(async () => {
    const p = await page.evaluate(() => (window as any).__studio.vertexScreen(2));
    await page.mouse.click(p.x, p.y);
    await expect(page.getByTestId('vertex-index')).toHaveText('#2', { timeout: 3000 });
  }).toPass({ timeout: 30000 });
  await page.getByTestId('vertex-z').fill('0.4');
  await page.getByTestId('vertex-z').press('Enter');
  await expect.poll(async () => (await studio.state()).model.vertices[2][2]).toBeCloseTo(0.4, 6);
});

test('select a frame and move the a1 slider: the shape changes', async ({ page, studio }) => {
  await openStudio(page, studio);
  const f = await page.evaluate(() => (window as any).__studio.frameScreen(0));
  await page.mouse.click(f.x, f.y);
  await expect(page.getByTestId('frame-selection')).toHaveText('#0');
  await expect(page.getByTestId('a1-z')).toBeEnabled();
  await meshUpToDate(page);
  await page.waitForTimeout(300);
  const imageBefore = await surface(page).screenshot();

  // a1.z: the forces of sculpt.json push along z, so z is what a1.z reshapes.
  await page.getByTestId('a1-z').fill('0.3');
  await expect.poll(async () => (await studio.state()).model.frames[0].a1?.[2]).toBeCloseTo(0.3, 6);
  await expect(page.getByTestId('a1-z-value')).toHaveValue('0.3');
  await meshUpToDate(page);
  await page.waitForTimeout(300);
  const imageAfter = await surface(page).screenshot();
  expect(imageAfter.equals(imageBefore)).toBe(false);

  // Magnification: value = slider × magnification.
  await page.getByTestId('a1-y-mag').fill('3');
  await page.getByTestId('a1-y-mag').press('Enter');
  await expect.poll(async () => (await studio.state()).model.frames[0].a1?.[1]).toBeCloseTo(3, 6);
  // The value box: a typed expression sets the value exactly (no slider rounding), and the
  // slider's range follows it.
  await page.getByTestId('a1-y-value').fill('1/3');
  await page.getByTestId('a1-y-value').press('Enter');
  await expect.poll(async () => (await studio.state()).model.frames[0].a1?.[1]).toBe(1 / 3);
  await expect(page.getByTestId('a1-y-mag')).toHaveValue('1');

  // A force region and f0.
  await page.getByTestId('force-0-u1').fill('0.6');
  await page.getByTestId('force-0-u1').press('Enter');
  await expect
    .poll(async () => (await studio.state()).model.frames[0].forces[0].region[1])
    .toBeCloseTo(0.6, 6);
  await page.getByTestId('f0-z').fill('0.9');
  await expect
    .poll(async () => (await studio.state()).model.frames[0].forces[0].f0[2])
    .toBeCloseTo(-90, 6);
  await page.screenshot({ path: shot('slider.png') });
  await expect(page.getByTestId('error')).toHaveText('');
});

test.describe('shared forces', () => {
  test.use({ example: 'grid-forces.json' });

  test('shift-click selects several frames; f0 sets a shared force', async ({ page, studio }) => {
    await openStudio(page, studio);
    const a = await page.evaluate(() => (window as any).__studio.frameScreen(0));
    const b = await page.evaluate(() => (window as any).__studio.frameScreen(1));
    await page.mouse.click(a.x, a.y);
    await page.keyboard.down('Shift');
    await page.mouse.click(b.x, b.y);
    await page.keyboard.up('Shift');
    await expect(page.getByTestId('frame-selection')).toHaveText('#0 #1');
    await page.getByTestId('f0-z').fill('0.5');
    await expect
      .poll(async () => (await studio.state()).model.forces?.find((f: any) => f.frames.length === 2))
      .toEqual({ f0: [0, 0, 0.5], frames: [0, 1] });
    await page.screenshot({ path: shot('shared-force.png') });
  });
});

test('save as, open another model and reopen it: the same model', async ({ page, studio }) => {
  await openStudio(page, studio);
  await dragVertex(page, 1, 30, -30, 5);
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  const edited = (await studio.state()).model;

  await page.getByTestId('saveas-path').fill('saved/copy.json');
  await page.getByTestId('save-as').click();
  await expect(page.getByTestId('model-path')).toHaveText('saved/copy.json');
  await expect(page.getByTestId('dirty')).toBeHidden();
  expect(existsSync(path.join(studio.root, 'saved', 'copy.json'))).toBe(true);

  await page.getByTestId('file-select').selectOption('sculpt.json');
  await page.getByTestId('open').click();
  await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
  expect((await studio.state()).model).not.toEqual(edited);

  await page.getByTestId('file-select').selectOption('saved/copy.json');
  await page.getByTestId('open').click();
  await expect(page.getByTestId('model-path')).toHaveText('saved/copy.json');
  expect((await studio.state()).model).toEqual(edited);

  // Save writes the file of the session.
  await page.getByTestId('save').click();
  await expect(page.getByTestId('status')).toContainText('saved saved/copy.json');
});

test('export OBJ, STL and glb under the root', async ({ page, studio }) => {
  await openStudio(page, studio);
  for (const ext of ['obj', 'stl', 'glb']) {
    await page.getByTestId(`export-${ext}`).click();
    await expect(page.getByTestId('status')).toContainText(`exported sculpt.${ext}`);
    const file = path.join(studio.root, `sculpt.${ext}`);
    expect(existsSync(file)).toBe(true);
    expect(statSync(file).size).toBeGreaterThan(100);
  }
});

test('an invalid edit shows the error and the page goes on working', async ({ page, studio }) => {
  await openStudio(page, studio);
  const error = await page.evaluate(() =>
    (window as any).__studio.edit({ op: 'move-vertex', vertex: 9999, position: [0, 0, 0] }),
  );
  expect(error).toContain('out of range');
  await expect(page.getByTestId('error')).toContainText('out of range');
  await expect(page.getByTestId('status')).toContainText('8 vertices');
  await page.screenshot({ path: shot('error.png') });

  // A raw request (with the page's token) is refused the same way, and the model stays.
  const status = await page.evaluate(async () => {
    const r = await fetch('/api/edit', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', 'X-Pdesurf-Token': sessionStorage.getItem('pdesurf-token') ?? '' },
      body: JSON.stringify({ op: 'move-vertex', vertex: 9999, position: [0, 0, 0] }),
    });
    return r.status;
  });
  expect(status).toBe(400);
  expect((await studio.state()).revision).toBe(0);

  // Still works: a drag is accepted and clears the error.
  await dragVertex(page, 3, 20, -20, 4);
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  await expect(page.getByTestId('error')).toHaveText('');
  await meshUpToDate(page);
  const s = await pageState(page);
  expect(s.error).toBe('');
});

test('Live off: edits wait for Create', async ({ page, studio }) => {
  await openStudio(page, studio);
  await page.getByTestId('live').uncheck();
  await dragVertex(page, 4, 0, -40, 4);
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  await expect(page.getByTestId('status')).toContainText('out of date');
  const s = await pageState(page);
  expect(s.mesh).not.toBe(s.revision);
  await page.getByTestId('create').click();
  await meshUpToDate(page);
});

test('recovery: an autosave that differs from the file is offered', async ({ page, studio }) => {
  const fs = await import('node:fs');
  const model = JSON.parse(fs.readFileSync(studio.model, 'utf8'));
  model.vertices[4][2] = 0.5;
  fs.writeFileSync(`${studio.model}.autosave`, JSON.stringify(model));
  // The server looks for a journal when a model is opened: open the file again.
  await page.goto(studio.url);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('file-select').selectOption('sculpt.json');
  await page.getByTestId('open').click();
  await expect(page.getByTestId('recovery')).toBeVisible();
  await page.getByTestId('recover').click();
  await expect(page.getByTestId('recovery')).toBeHidden();
  await expect.poll(async () => (await studio.state()).model.vertices[4][2]).toBe(0.5);
});

test.describe('a spectral model', () => {
  test.use({ example: 'shell.json' });
  test('is shown, exported and refuses a vertex edit', async ({ page, studio }) => {
    await openStudio(page, studio);
    await expect(page.getByTestId('status')).toContainText('spectral model: drag its handles');
    await expect(page.getByTestId('status')).toContainText('triangles');
    expect((await studio.state()).hasEditableParts).toBe(false);
    await expect(page.getByTestId('frame-caption')).toHaveText('Curves and spine');
    await expect(page.getByTestId('frame-tools')).toBeHidden();
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('shell.png') });
    const error = await page.evaluate(() =>
      (window as any).__studio.edit({ op: 'move-vertex', vertex: 0, position: [0, 0, 0] }),
    );
    expect(error).toContain('vertex-frame models');
    await page.getByTestId('export-obj').click();
    await expect(page.getByTestId('status')).toContainText('exported shell.obj');
    expect(existsSync(path.join(studio.root, 'shell.obj'))).toBe(true);
  });
});

test.describe('transforming a spectral model', () => {
  test.use({ example: 'shell.json' });
  test('Move shifts the surface; the page mesh is the server mesh; undo puts it back', async ({ page, studio }) => {
    await openStudio(page, studio);
    const box = () => page.evaluate(() => (window as any).__studio.meshBox());
    const before = await box();
    await page.getByTestId('move-x').fill('1');
    await page.getByTestId('move-y').fill('0');
    await page.getByTestId('move-z').fill('-0.5');
    await page.getByTestId('move-apply').click();
    await expect(page.getByTestId('status')).toContainText('moved the model');
    await meshUpToDate(page);
    expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);
    const after = await box();
    const shift = [1, 0, -0.5];
    for (let c = 0; c < 3; ++c) {
      expect(after.min[c]).toBeCloseTo(before.min[c] + shift[c], 4);
      expect(after.max[c]).toBeCloseTo(before.max[c] + shift[c], 4);
    }
    const s = await studio.state();
    expect(s.hasEditableParts).toBe(false);
    expect(s.undo).toBe(1);
    expect(s.dirty).toBe(true);
    expect(s.model.type).toBe('spectral');
    await expect(page.getByTestId('error')).toHaveText('');
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('shell-moved.png') });

    // Scale about the centre keeps the centre; undo twice is the opened surface again.
    await page.getByTestId('scale-factor').fill('0.5');
    await page.getByTestId('scale-apply').click();
    await expect(page.getByTestId('status')).toContainText('scaled the model');
    await meshUpToDate(page);
    const scaled = await box();
    for (let c = 0; c < 3; ++c) {
      expect((scaled.min[c] + scaled.max[c]) / 2).toBeCloseTo((after.min[c] + after.max[c]) / 2, 3);
      expect(scaled.max[c] - scaled.min[c]).toBeCloseTo((after.max[c] - after.min[c]) / 2, 3);
    }
    await page.getByTestId('undo').click();
    await expect.poll(async () => (await studio.state()).undo).toBe(1);
    await page.getByTestId('undo').click();
    await expect.poll(async () => (await studio.state()).undo).toBe(0);
    await meshUpToDate(page);
    const back = await box();
    for (let c = 0; c < 3; ++c) expect(back.min[c]).toBeCloseTo(before.min[c], 5);
    expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);
  });
});

test('Rotate turns a vertex-frame model about its centre: one undo step', async ({ page, studio }) => {
  await openStudio(page, studio);
  const box = () => page.evaluate(() => (window as any).__studio.meshBox());
  const before = await box();
  const vertices = (await studio.state()).model.vertices;
  await page.getByTestId('rotate-axis').selectOption('z');
  await page.getByTestId('rotate-degrees').fill('90');
  await page.getByTestId('rotate-apply').click();
  await expect(page.getByTestId('status')).toContainText('rotated the model');
  await meshUpToDate(page);
  expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);
  const after = await box();
  const c = [0, 1, 2].map((i) => (before.min[i] + before.max[i]) / 2);
  // A quarter turn about z: x and y extents swap, the centre stays.
  expect(after.max[0] - after.min[0]).toBeCloseTo(before.max[1] - before.min[1], 4);
  expect(after.max[1] - after.min[1]).toBeCloseTo(before.max[0] - before.min[0], 4);
  for (let i = 0; i < 3; ++i) expect((after.min[i] + after.max[i]) / 2).toBeCloseTo(c[i], 4);
  const s = await studio.state();
  expect(s.undo).toBe(1);
  const [x, y] = vertices[0];
  expect(s.model.vertices[0][0]).toBeCloseTo(c[0] - (y - c[1]), 9);
  expect(s.model.vertices[0][1]).toBeCloseTo(c[1] + (x - c[0]), 9);
  await page.waitForTimeout(300);
  await page.screenshot({ path: shot('sculpt-rotated.png') });
  await page.getByTestId('undo').click();
  await expect.poll(async () => (await studio.state()).model.vertices).toEqual(vertices);
});

test.describe('a B-spline PDE model', () => {
  test.use({ example: 'bspline-blend.json' });
  test('shows its control nets and surface, and scales as a whole', async ({ page, studio }) => {
    await openStudio(page, studio);
    await expect(page.getByTestId('status')).toContainText('bspline-pde model: drag its handles');
    await expect(page.getByTestId('frame-caption')).toHaveText('Control nets');
    await expect(page.getByTestId('frame-tools')).toBeHidden();  // no vertices, frames, forces
    await meshUpToDate(page);
    expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);
    const box = () => page.evaluate(() => (window as any).__studio.meshBox());
    const before = await box();
    await page.getByTestId('scale-factor').fill('2');
    await page.getByTestId('scale-apply').click();
    // The session's revision changes only when the answer arrives: wait for it first, or
    // the old mesh still matches the old revision.
    await expect(page.getByTestId('status')).toContainText('scaled the model');
    await meshUpToDate(page);
    expect(await page.evaluate(() => (window as any).__studio.meshMatchesServer())).toBe(true);
    const after = await box();
    for (let c = 0; c < 3; ++c)  // scaled about the box centre: twice as wide, same centre
      expect(after.max[c] - after.min[c]).toBeCloseTo(2 * (before.max[c] - before.min[c]), 4);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('bspline-blend.png') });
  });
});
