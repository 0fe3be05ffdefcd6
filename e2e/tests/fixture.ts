// A `pdesurf studio` per test: a temporary root with a copy of an example, the server on
// a free port (its URL, with the per-launch token, is the first line it prints), stopped
// (SIGTERM) when the test ends.
import { test as base, expect, type Page } from '@playwright/test';
import { spawn, type ChildProcess } from 'node:child_process';
import { copyFileSync, mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { createInterface } from 'node:readline';

export const SOURCE_DIR = path.resolve(__dirname, '..', '..');
export const CLI = process.env.PDESURF_CLI || path.join(SOURCE_DIR, 'build', 'pdesurf');
export const ARTIFACTS = path.resolve(__dirname, '..', 'artifacts');

export interface Studio {
  /** The URL the studio printed: http://127.0.0.1:PORT/?token=TOKEN. */
  url: string;
  /** http://127.0.0.1:PORT/ */
  origin: string;
  /** The per-launch token (the header X-Pdesurf-Token of every API request). */
  token: string;
  root: string;
  model: string;
  /** GET /api/model (with the token), parsed. */
  state(): Promise<any>;
}

/** The URL of the first line `pdesurf studio` prints, its origin and its token. */
export function printedUrl(line: string): { url: string; origin: string; token: string } {
  const m = /(http:\/\/[^/\s]+\/)\?token=([0-9a-f]+)/.exec(line);
  if (!m) throw new Error(`unexpected first line: ${line}`);
  return { url: `${m[1]}?token=${m[2]}`, origin: m[1], token: m[2] };
}

async function startStudio(example: string): Promise<{ studio: Studio; child: ChildProcess }> {
  const root = mkdtempSync(path.join(tmpdir(), 'pdesurf-e2e-'));
  const model = path.join(root, example);
  copyFileSync(path.join(SOURCE_DIR, 'examples', example), model);
  const child = spawn(CLI, ['studio', model, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr!.on('data', (d) => (stderr += d));
  const line = await new Promise<string>((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`studio did not start: ${stderr}`)), 15_000);
    child.on('exit', (code) => reject(new Error(`studio exited with ${code}: ${stderr}`)));
    createInterface({ input: child.stdout! }).once('line', (first) => {
      clearTimeout(timer);
      resolve(first);
    });
  });
  const { url, origin, token } = printedUrl(line);
  const studio: Studio = {
    url,
    origin,
    token,
    root,
    model,
    state: async () => (await fetch(`${origin}api/model`, { headers: { 'X-Pdesurf-Token': token } })).json(),
  };
  return { studio, child };
}

export const test = base.extend<{ example: string; studio: Studio }>({
  example: ['sculpt.json', { option: true }],
  studio: async ({ example }, use) => {
    const { studio, child } = await startStudio(example);
    try {
      await use(studio);
    } finally {
      const exited = new Promise((r) => child.once('exit', r));
      child.kill('SIGTERM');
      await Promise.race([exited, new Promise((r) => setTimeout(r, 3000))]);
      if (child.exitCode === null) child.kill('SIGKILL');
      rmSync(studio.root, { recursive: true, force: true });
    }
  },
});

export { expect };

/** Opens the studio and waits until the model and its first mesh are shown. */
export async function openStudio(page: Page, studio: Studio): Promise<void> {
  const errors: string[] = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(studio.url);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('c0-gap')).toContainText('C0 gap');
  expect(errors).toEqual([]);
}

export function shot(name: string): string {
  mkdirSync(ARTIFACTS, { recursive: true });
  return path.join(ARTIFACTS, name);
}

/** The revision of the last mesh the page drew and of the session. */
export async function pageState(page: Page): Promise<{ revision: number; mesh: number; error: string }> {
  return page.evaluate(() => (window as any).__studio.state());
}

/** Waits until the page shows the mesh of the session's current revision. */
export async function meshUpToDate(page: Page): Promise<void> {
  await expect
    .poll(async () => {
      const s = await pageState(page);
      return s.mesh === s.revision;
    })
    .toBe(true);
}

/** Waits until every edit the page queued is answered (a drag's last move included). */
export async function settle(page: Page): Promise<void> {
  await page.evaluate(() => (window as any).__studio.idle());
}

/** Drags vertex `vertex`'s handle in the frame view by (dx, dy) pixels in `steps` moves,
 * then waits until the page's edits are answered. */
export async function dragVertex(page: Page, vertex: number, dx: number, dy: number, steps: number): Promise<void> {
  const p = await page.evaluate((v) => (window as any).__studio.vertexScreen(v), vertex);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await page.mouse.move(p.x + dx, p.y + dy, { steps });
  await page.mouse.up();
  await settle(page);
}

/** Makes a new model through the New… dialog (the modeller's specs). */
export async function newModel(page: Page, kind: string, file: string, u = 1, v = 1): Promise<void> {
  await page.getByTestId('new-model').click();
  await page.getByTestId('new-kind').selectOption(kind);
  await page.getByTestId('new-u').fill(String(u));
  await page.getByTestId('new-v').fill(String(v));
  await page.getByTestId('new-path').fill(file);
  await page.getByTestId('new-create').click();
  await expect(page.getByTestId('model-path')).toHaveText(file);
  await expect(page.getByTestId('c0-gap')).toContainText('C0 gap');
}

/** Clicks frame `frame`'s patch in the surface view (shift: adds it to the selection). */
export async function clickPatch(page: Page, frame: number, shift = false): Promise<void> {
  await expect(async () => {
    const q = await page.evaluate((f) => (window as any).__studio.patchScreen(f), frame);
    if (shift) await page.keyboard.down('Shift');
    await page.mouse.click(q.x, q.y);
    if (shift) await page.keyboard.up('Shift');
    expect((await page.evaluate(() => (window as any).__studio.selection())).frames).toContain(frame);
  }).toPass({ timeout: 30000 });
}
