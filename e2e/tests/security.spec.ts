// The studio and other web pages (apps/studio/README.md, "Security"): the page works from
// the printed URL and keeps its token out of the address bar; a page of another origin, or
// of another name resolving to 127.0.0.1 (DNS rebinding), can neither change nor read the
// model.
import { chromium } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { dragVertex, expect, openStudio, test } from './fixture';

test('the printed URL opens the studio; the token leaves the address bar and survives a reload', async ({ page, studio }) => {
  await openStudio(page, studio);
  expect(page.url()).toBe(studio.origin);
  expect(await page.evaluate(() => sessionStorage.getItem('pdesurf-token'))).toBe(studio.token);
  await dragVertex(page, 3, 20, -20, 4);
  await expect.poll(async () => (await studio.state()).undo).toBe(1);
  // A reload (no token in the address now) keeps working, and so does Save.
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('status')).toContainText('undo 1');
  await page.getByTestId('save').click();
  await expect.poll(async () => (await studio.state()).dirty).toBe(false);
  await expect(page.getByTestId('error')).toHaveText('');
});

test('without the token the page says where to find it', async ({ page, studio }) => {
  await page.goto(studio.origin);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('error')).toContainText('?token=');
});

/** Serves one HTML page on 127.0.0.1 at a free port: another origin than the studio's. */
async function servePage(html: string): Promise<{ server: Server; url: string }> {
  const server = createServer((_req, res) => {
    res.writeHead(200, { 'Content-Type': 'text/html' });
    res.end(html);
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, url: `http://127.0.0.1:${(server.address() as AddressInfo).port}/` };
}

test('another web page can neither change nor read the model', async ({ page, studio }) => {
  const before = readFileSync(studio.model);
  // What the issue measured: "simple" POSTs (text/plain: no preflight) of a transform and a
  // save; then a JSON POST (preflighted), a read, a form post, each as a page may try.
  const attack = `<!doctype html><script>
    window.done = (async () => {
      const target = ${JSON.stringify(studio.origin)};
      const out = {};
      const simple = (path, body) =>
        fetch(target + path, { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'text/plain' }, body })
          .then((r) => r.type, (e) => 'failed: ' + e);
      out.transform = await simple('api/transform', '{"scale": 3}');
      out.save = await simple('api/save', '{}');
      out.json = await fetch(target + 'api/transform', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: '{"scale": 3}' })
        .then((r) => r.status, (e) => 'blocked');
      out.read = await fetch(target + 'api/model').then((r) => r.text(), (e) => 'blocked');
      out.readNoCors = await fetch(target + 'api/model', { mode: 'no-cors' }).then((r) => r.type, (e) => 'failed');
      const frame = document.createElement('iframe');
      frame.name = 'sink';
      document.body.append(frame);
      const form = Object.assign(document.createElement('form'), { method: 'POST', action: target + 'api/save', target: 'sink', enctype: 'text/plain' });
      document.body.append(form);
      const loaded = new Promise((r) => frame.addEventListener('load', r, { once: true }));
      form.submit();
      await Promise.race([loaded, new Promise((r) => setTimeout(r, 3000))]);
      return out;
    })();
  </script>`;
  const { server, url } = await servePage(attack);
  try {
    await page.goto(url);
    const out = await page.evaluate(() => (window as any).done);
    // The simple requests went out (opaque answers), the others were stopped by the
    // browser (no CORS grant) or refused; nothing was read.
    expect(out.transform).toBe('opaque');
    expect(out.save).toBe('opaque');
    expect(out.json).toBe('blocked');
    expect(out.read).toBe('blocked');
    expect(out.readNoCors).toBe('opaque');
    const state = await studio.state();
    expect(state.revision).toBe(0);
    expect(state.undo).toBe(0);
    expect(state.dirty).toBe(false);
    expect(readFileSync(studio.model).equals(before)).toBe(true);
  } finally {
    server.close();
  }
});

test('a name that resolves to 127.0.0.1 (DNS rebinding) gets neither the page nor the model', async ({ studio }) => {
  const port = new URL(studio.origin).port;
  // Chromium resolving rebind.test to 127.0.0.1, as a rebinding DNS server would.
  const browser = await chromium.launch({
    executablePath: process.env.PDESURF_CHROMIUM || '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--host-resolver-rules=MAP rebind.test 127.0.0.1'],
  });
  try {
    const page = await browser.newPage();
    const answer = await page.goto(`http://rebind.test:${port}/?token=${studio.token}`);
    expect(answer?.status()).toBe(403);
    expect(await answer?.text()).toContain('is not this studio');
    // Even a page of that name holding the token (stolen) reads nothing.
    const read = await page.evaluate(async (token) => {
      const r = await fetch('/api/model', { headers: { 'X-Pdesurf-Token': token } });
      return r.status;
    }, studio.token);
    expect(read).toBe(403);
  } finally {
    await browser.close();
  }
  expect((await studio.state()).revision).toBe(0);
});
