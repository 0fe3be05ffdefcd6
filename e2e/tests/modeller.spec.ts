// The modeller, as a user does it: a new model from the toolbar, vertices picked by click and
// box, structure edits by key and button, patches picked on the surface, the selection moved
// by a drag and by a typed offset; the saved file's structure checked, and every structure
// edit undone byte for byte.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { expect, meshUpToDate, newModel, openStudio, settle, shot, test } from './fixture';
import type { Studio } from './fixture';

/** What a C0 gap "at rounding level" is for these models (a few units across): the library's
 * kC0RelativeTolerance (include/pdesurf/analysis.hpp) times a size below 10. */
const ROUNDING_GAP = 1e-11;

const hooks = (page: Page) => ({
  vertexScreen: (v: number) => page.evaluate((i) => (window as any).__studio.vertexScreen(i), v),
  patchScreen: (f: number) => page.evaluate((i) => (window as any).__studio.patchScreen(i), f),
  selection: () => page.evaluate(() => (window as any).__studio.selection()),
});

/** The sides two frames share (by their three vertices). */
function sharedSides(model: { frames: { vertices: number[] }[] }): number {
  const slots = [[0, 1, 2], [2, 3, 4], [6, 5, 4], [0, 7, 6]];
  const count = new Map<string, number>();
  for (const f of model.frames)
    for (const s of slots) {
      const v = s.map((i) => f.vertices[i]);
      const key = (v[0] < v[2] ? v : [...v].reverse()).join('/');
      count.set(key, (count.get(key) ?? 0) + 1);
    }
  return [...count.values()].filter((n) => n === 2).length;
}

/** Ctrl+Z once the page's Undo is enabled: the page enables it from the answer to the edit
 * before, which can come after the server already shows that edit. */
async function undoKey(page: Page): Promise<void> {
  await expect(page.getByTestId('undo')).toBeEnabled();
  await page.keyboard.press('Control+z');
}

/** A click at a client point, with shift held when `shift` (mouse.click takes no modifiers). */
async function shiftClick(page: Page, p: { x: number; y: number }, shift: boolean): Promise<void> {
  if (shift) await page.keyboard.down('Shift');
  await page.mouse.click(p.x, p.y);
  if (shift) await page.keyboard.up('Shift');
}

/** Clicks vertex handles: the first alone, the others with shift (added). Software WebGL on a
 * loaded machine can drop a click while a frame renders: clicks again until the selection is
 * what was picked (the selection itself is what the tests assert). */
async function pickVertices(page: Page, vertices: number[]): Promise<void> {
  await expect(async () => {
    await page.keyboard.press('Escape');
    for (const [i, v] of vertices.entries()) {
      const p = await hooks(page).vertexScreen(v);
      await shiftClick(page, p, i > 0);
    }
    expect((await hooks(page).selection()).vertices).toEqual(vertices);
  }).toPass({ timeout: 30000 });
}

/** Selects frame `f` by clicking its patch on the surface. */
async function pickPatch(page: Page, f: number, add = false): Promise<void> {
  await expect(async () => {
    const p = await hooks(page).patchScreen(f);
    await shiftClick(page, p, add);
    expect((await hooks(page).selection()).frames).toContain(f);
  }).toPass({ timeout: 30000 });
}

async function frames(studio: Studio): Promise<number> {
  return (await studio.state()).model.frames.length;
}

const fileText = (studio: Studio, name: string) => readFileSync(path.join(studio.root, name), 'utf8');

// These tests do a user's many steps in software WebGL: more time than the default 60 s.
test.describe.configure({ timeout: 240_000 });

test('build an L of 3 frames from nothing: new, box select, extrude twice, save, reopen, undo', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'single', 'l.json');
  const fresh = fileText(studio, 'l.json');
  expect(await frames(studio)).toBe(1);

  // The u = 1 side (the frame's P3, P4, P5) by a shift+drag box.
  await page.getByTestId('view-top').click();
  const side: number[] = (await studio.state()).model.frames[0].vertices.slice(2, 5);
  const a = await hooks(page).vertexScreen(side[0]);
  const b = await hooks(page).vertexScreen(side[2]);
  await page.mouse.move(a.x + 12, a.y + 12);
  await page.keyboard.down('Shift');
  await page.mouse.down();
  await page.mouse.move(b.x - 12, b.y - 12, { steps: 5 });
  await page.screenshot({ path: shot('modeller-box.png') });
  await page.mouse.up();
  await page.keyboard.up('Shift');
  expect((await hooks(page).selection()).vertices.sort()).toEqual([...side].sort());
  await page.keyboard.press('e');
  await expect.poll(() => frames(studio)).toBe(2);

  // The new frame's v = 1 side: its P7 and P5, picked by clicks (the new frame in view).
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  const m = (await studio.state()).model;
  await pickVertices(page, [m.frames[1].vertices[6], m.frames[1].vertices[4]]);
  await page.getByTestId('extrude').click();
  await expect.poll(() => frames(studio)).toBe(3);
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(300);
  await page.screenshot({ path: shot('modeller-l-shape.png') });

  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('dirty')).toBeHidden();
  const lShape = fileText(studio, 'l.json');
  const saved = JSON.parse(lShape);
  expect(saved.frames).toHaveLength(3);
  expect(sharedSides(saved)).toBe(2);

  // Reopened: 3 frames, the shared edges, the C0 gap at rounding level.
  await page.getByTestId('file-select').selectOption('sculpt.json');
  await page.getByTestId('open').click();
  await expect(page.getByTestId('model-path')).toHaveText('sculpt.json');
  await page.getByTestId('file-select').selectOption('l.json');
  await page.getByTestId('open').click();
  await expect(page.getByTestId('model-path')).toHaveText('l.json');
  await expect(page.getByTestId('status')).toContainText('3 frames');
  await expect(page.getByTestId('c0-gap')).toContainText('C0 gap');
  const gap = Number((await page.getByTestId('c0-gap').textContent())!.replace(/^C0 gap\s*/, '').split(' ')[0]);
  expect(gap).toBeLessThan(ROUNDING_GAP);

  // Each structure edit undone: the files are byte for byte those before it.
  await pickVertices(page, [saved.frames[2].vertices[6], saved.frames[2].vertices[4]]);
  await page.keyboard.press('e');
  await expect.poll(() => frames(studio)).toBe(4);
  await undoKey(page);
  await expect.poll(() => frames(studio)).toBe(3);
  await page.keyboard.press('Control+s');
  await expect.poll(() => fileText(studio, 'l.json')).toBe(lShape);
  await pickPatch(page, 1);
  await page.keyboard.press('x');
  await expect.poll(() => frames(studio)).toBe(2);
  await undoKey(page);
  await page.keyboard.press('Control+s');
  await expect.poll(() => fileText(studio, 'l.json')).toBe(lShape);
  expect(fresh).not.toBe(lShape);
});

test('split, flip, weld, delete and add a frame on a grid; each undone', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'grid.json', 3, 1);
  const grid = fileText(studio, 'grid.json');
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(200);

  /** Applies a tool, checks the frame count, undoes it and checks the file byte for byte. */
  const roundTrip = async (act: () => Promise<void>, framesAfter: number, picture: string) => {
    await act();
    await expect.poll(() => frames(studio)).toBe(framesAfter);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot(picture) });
    await undoKey(page);
    await expect.poll(() => frames(studio)).toBe(3);
    await page.keyboard.press('Control+s');
    await expect.poll(() => fileText(studio, 'grid.json')).toBe(grid);
  };

  // Split the middle frame in 4: the cut across v runs on through both neighbours (2 each).
  await pickPatch(page, 1);
  await expect(page.getByTestId('frame-selection')).toHaveText('#1');
  await roundTrip(() => page.keyboard.press('s'), 4 + 2 + 2, 'modeller-split.png');
  await pickPatch(page, 1);
  await roundTrip(() => page.getByTestId('split-u').click(), 4, 'modeller-split-u.png');

  // Flip: same frames, P1 and P3 exchanged.
  await pickPatch(page, 2);
  const before = (await studio.state()).model.frames[2].vertices;
  await page.keyboard.press('r');
  await expect.poll(async () => (await studio.state()).model.frames[2].vertices[0]).toBe(before[2]);
  await meshUpToDate(page); // the page has taken the flip in
  await page.getByTestId('undo').click();
  await expect.poll(async () => (await studio.state()).model.frames[2].vertices[0]).toBe(before[0]);

  // Weld the two ends (u = 0 of frame 0, u = 1 of frame 2): a tube of 3 frames.
  const m = (await studio.state()).model;
  const ends = [m.frames[0].vertices[0], m.frames[0].vertices[6], m.frames[2].vertices[2], m.frames[2].vertices[4]];
  await pickVertices(page, ends);
  const vertices = m.vertices.length;
  await page.keyboard.press('w');
  await expect.poll(async () => (await studio.state()).model.vertices.length).toBe(vertices - 3);
  expect(sharedSides((await studio.state()).model)).toBe(3);
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(300);
  await page.screenshot({ path: shot('modeller-weld.png') });
  await undoKey(page);
  await expect.poll(async () => (await studio.state()).model.vertices.length).toBe(vertices);
  await page.getByTestId('view-top').click();
  await page.waitForTimeout(200);

  // Delete the middle frame, then add a frame on its four corners, picked clockwise (the
  // studio turns it to face as its neighbours): the strip is whole again.
  const corners = [m.frames[1].vertices[0], m.frames[1].vertices[6], m.frames[1].vertices[4], m.frames[1].vertices[2]];
  await pickPatch(page, 1);
  await page.keyboard.press('x');
  await expect.poll(() => frames(studio)).toBe(2);
  const after = (await studio.state()).model;
  expect(sharedSides(after)).toBe(0);
  // Vertex indices above the two removed middles moved down by 2.
  const renumber = (v: number) => v - [m.frames[1].vertices[1], m.frames[1].vertices[5]].filter((x) => x < v).length;
  await pickVertices(page, corners.map(renumber));
  await page.keyboard.press('a');
  await expect.poll(() => frames(studio)).toBe(3);
  expect(sharedSides((await studio.state()).model)).toBe(2);
  await page.screenshot({ path: shot('modeller-add-frame.png') });
  await undoKey(page);
  await undoKey(page);
  await expect.poll(() => frames(studio)).toBe(3);
  await page.keyboard.press('Control+s');
  await expect.poll(() => fileText(studio, 'grid.json')).toBe(grid);

  // A refused edit says why in the error line and changes nothing.
  await pickVertices(page, [m.frames[0].vertices[2], m.frames[0].vertices[4]]); // a shared side
  await page.keyboard.press('e');
  await expect(page.getByTestId('error')).toContainText('Extrude: select both corners');
});

test('move a selection: drag one of its handles, or type an offset; one undo step each', async ({ page, studio }) => {
  await openStudio(page, studio);
  await newModel(page, 'grid', 'move.json', 2, 1);
  await page.getByTestId('view-iso').click();
  await page.waitForTimeout(200);
  const m = (await studio.state()).model;
  const picked = [m.frames[0].vertices[5], m.frames[0].vertices[6]];
  await pickVertices(page, picked);
  await expect(page.getByTestId('vertex-selection')).toHaveText('2 vertices');

  const p = await hooks(page).vertexScreen(picked[0]);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(p.x, p.y - 60, { steps: 6 });
  await page.mouse.up();
  await settle(page);
  const moved = (await studio.state()).model;
  const offset = (v: number) => moved.vertices[v].map((x: number, i: number) => x - m.vertices[v][i]);
  expect(Math.hypot(...offset(picked[0]))).toBeGreaterThan(0.05);
  // Both moved by the same offset (in the plane facing the camera); nothing else moved.
  offset(picked[1]).forEach((d: number, i: number) => expect(d).toBeCloseTo(offset(picked[0])[i], 9));
  expect(moved.vertices[m.frames[0].vertices[0]]).toEqual(m.vertices[m.frames[0].vertices[0]]);
  expect((await studio.state()).undo).toBe(1);
  await page.screenshot({ path: shot('modeller-drag-selection.png') });

  // A typed offset moves the selected frame's vertices.
  await page.keyboard.press('Escape');
  await pickPatch(page, 1);
  await page.getByTestId('offset-x').fill('0');
  await page.getByTestId('offset-y').fill('0');
  await page.getByTestId('offset-z').fill('0.5');
  await page.getByTestId('offset-apply').click();
  await expect.poll(async () => (await studio.state()).model.vertices[m.frames[1].vertices[4]][2]).toBeCloseTo(m.vertices[m.frames[1].vertices[4]][2] + 0.5, 9);
  expect((await studio.state()).undo).toBe(2);
  await undoKey(page);
  await expect.poll(async () => (await studio.state()).model.vertices[m.frames[1].vertices[4]][2]).toBe(m.vertices[m.frames[1].vertices[4]][2]);
});
