// The a1 / a2 note and the local solver (issue 17): on a force-free frame inside the mug's
// long strips, a1 barely moves the global solver's surface (the strip's cubic is fitted
// to all its frames); with the local solver seeded at that frame, the frame's own a1 / a2
// set its strips, and the same slider move reshapes its patch visibly more.
import type { Page } from '@playwright/test';
import { expect, meshUpToDate, openStudio, settle, shot, test } from './fixture';

const hooks = (page: Page, name: string, ...args: unknown[]) =>
  page.evaluate(([n, a]) => (window as any).__studio[n as string](...(a as unknown[])), [name, args] as const);

/** A body frame of the mug (no forces; its strips run around and along the body). */
const FRAME = 21;
/** How much more the local solver must move the frame's patch than the global one: "visibly
 * more" (the measured ratio on the mug is far above it: docs/studio.md). */
const MIN_RATIO = 3;

/** The largest distance a mesh vertex inside `box` (the frame's vertices' bounding box)
 * moved between two meshes of the same layout. */
function moved(before: number[], after: number[], box: { min: number[]; max: number[] }): number {
  expect(after.length).toBe(before.length);
  let most = 0;
  for (let i = 0; i < before.length; i += 3) {
    let inside = true;
    for (let c = 0; c < 3; ++c) inside &&= before[i + c] >= box.min[c] && before[i + c] <= box.max[c];
    if (!inside) continue;
    most = Math.max(most, Math.hypot(after[i] - before[i], after[i + 1] - before[i + 1], after[i + 2] - before[i + 2]));
  }
  return most;
}

/** Sets a1.x of the selected frame through its slider; the surface it gives. */
async function setA1(page: Page, value: string): Promise<number[]> {
  await page.getByTestId('a1-x').fill(value);
  await settle(page);
  await meshUpToDate(page);
  await hooks(page, 'meshIdle');
  return hooks(page, 'meshPositions');
}

test.describe('the local solver', () => {
  test.use({ example: 'mug.json' });

  test('with the local solver seeded at the selected frame, a1 moves its patch visibly more', async ({ page, studio }) => {
    test.setTimeout(120_000); // four surfaces of the mug at Res 24, an undo, on a shared machine
    await openStudio(page, studio);
    const model = (await studio.state()).model;
    const corners = model.frames[FRAME].vertices.map((v: number) => model.vertices[v]);
    const box = {
      min: [0, 1, 2].map((c) => Math.min(...corners.map((p: number[]) => p[c]))),
      max: [0, 1, 2].map((c) => Math.max(...corners.map((p: number[]) => p[c]))),
    };
    const f = await hooks(page, 'frameScreen', FRAME);
    await page.mouse.click(f.x, f.y);
    await expect(page.getByTestId('frame-selection')).toHaveText(`#${FRAME}`);
    await expect(page.getByTestId('parameters-note')).toContainText('long strip');
    await meshUpToDate(page);

    // The global solver (the default).
    const global0: number[] = await hooks(page, 'meshPositions');
    const global1 = await setA1(page, '0.1');
    const dGlobal = moved(global0, global1, box);
    await page.getByTestId('undo').click();
    await expect.poll(async () => (await studio.state()).undo).toBe(0);
    await meshUpToDate(page);

    // The local solver, its seed the selected frame.
    await page.getByTestId('local-solver').check();
    await expect(page.getByTestId('seed-frame')).toHaveValue(String(FRAME));
    await expect(page.getByTestId('seed-frame')).toBeEnabled();
    await hooks(page, 'meshIdle');
    const local0: number[] = await hooks(page, 'meshPositions');
    expect(moved(global0, local0, { min: [-Infinity, -Infinity, -Infinity], max: [Infinity, Infinity, Infinity] })).toBeGreaterThan(0);
    const local1 = await setA1(page, '0.1');
    const dLocal = moved(local0, local1, box);
    console.log(`a1.x 1 -> 0.1 on frame ${FRAME}: its patch moved ${dGlobal.toExponential(3)} (global), ${dLocal.toExponential(3)} (local)`);
    expect(dLocal).toBeGreaterThan(MIN_RATIO * dGlobal);
    expect(await hooks(page, 'meshMatchesServer')).toBe(true);
    await page.waitForTimeout(300);
    await page.screenshot({ path: shot('local-solver-mug.png') });

    // A seed the model does not have is refused in place; nothing is asked of the server.
    await page.getByTestId('seed-frame').fill('99');
    await page.getByTestId('seed-frame').press('Enter');
    await expect(page.getByTestId('seed-frame')).toHaveClass(/invalid/);
    await expect(page.getByTestId('error')).toContainText('seed frame: must be at most 61');
  });
});
