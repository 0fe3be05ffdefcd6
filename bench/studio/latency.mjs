// Studio edit-to-new-frame latency (docs/performance.md, "Studio: edit to new frame").
// Starts `pdesurf studio` on a generated 1,000-frame model, opens it in Debian's chromium
// (the launch of e2e/playwright.config.ts) through e2e's Playwright, sets Res 16 and drags
// one vertex with real mouse events. In the page it times, for every edit, the pointer
// event (a capture pointermove listener on the frame view's canvas) to the first
// requestAnimationFrame callback after the surface mesh of that edit was applied.
//
// Usage: node bench/studio/latency.mjs [--cli build/pdesurf] [--steps 200] [--stream 300] [--json out.json]
//          [--model examples/mug.json] [--resolution 16] [--preview 1] [--releases 5] [--query K=V]
//   (scripts/run_bench_studio runs it with --steps 100 --stream 0; later options win)
//   --model: a model file instead of the generated sheet (the vertex dragged is the one
//   nearest the frame view's centre on screen); --preview 0: the page without its adaptive
//   preview (?preview=0), the baseline; --releases N: N more drags, each timed from the
//   button's release (pointerup on the frame view's canvas) to the first animation frame
//   whose surface mesh is at the chosen resolution, then a pixel read back from the surface
//   view (which waits until its draw is done), with the release's splits (the mesh request,
//   its body, body to frame, each view's draws until neither drew for a second, the last
//   surface draw done and whether the boundary curves were back by then); --query: options
//   added to the page's URL (aa=1, say).
//
// Two runs: "step" moves the pointer once, waits until that edit's mesh is on screen, then
// idles 50 ms (one edit at a time: the latency of one edit); "stream" moves the pointer
// every 16.7 ms (a 60 Hz drag: edits are coalesced by the page, every pointer event is
// timed to the first frame showing a mesh at or past the edit that carried it).
import { spawn, execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { appendFileSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir, cpus, loadavg } from 'node:os';
import path from 'node:path';
import { createInterface } from 'node:readline';
import { fileURLToPath } from 'node:url';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const SOURCE = path.resolve(HERE, '..', '..');
const args = process.argv.slice(2);
if (args.includes('--help') || args.includes('-h')) {
  // The usage is the comment block at the top of this file.
  const head = readFileSync(fileURLToPath(import.meta.url), 'utf8').split('\n');
  const end = head.findIndex((line) => !line.startsWith('//'));
  console.log(head.slice(0, end).map((line) => line.replace(/^\/\/ ?/, '')).join('\n'));
  process.exit(0);
}
const require = createRequire(path.join(SOURCE, 'e2e', 'package.json'));
const { chromium } = require('@playwright/test');

const opt = (name, dflt) => {
  const i = args.lastIndexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : dflt;
};
const CLI = path.resolve(opt('cli', process.env.PDESURF_CLI || path.join(SOURCE, 'build', 'pdesurf')));
const STEPS = Number(opt('steps', 200));
const STREAM = Number(opt('stream', 300));
const RESOLUTION = opt('resolution', '16');
const JSON_OUT = opt('json', '');
const ROWS = Number(opt('rows', 25)), COLS = Number(opt('cols', 40));
const MODEL = opt('model', '');
const PREVIEW = opt('preview', '1') !== '0';
const RELEASES = Number(opt('releases', 5));
const QUERY = opt('query', '');
/** A release's draws are over when neither view drew for this long. */
const SETTLE_MS = 1000;

// Same launch as e2e/playwright.config.ts.
const LAUNCH = {
  executablePath: process.env.PDESURF_CHROMIUM || '/usr/bin/chromium',
  args: [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  ],
};

async function startStudio(model) {
  const child = spawn(CLI, ['studio', model, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => (stderr += d));
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`studio did not start: ${stderr}`)), 15000);
    child.on('exit', (code) => reject(new Error(`studio exited with ${code}: ${stderr}`)));
    createInterface({ input: child.stdout }).once('line', (line) => {
      clearTimeout(timer);
      // The printed URL carries the per-launch token: the page takes it from there.
      const m = /(http:\/\/\S+\/\?token=[0-9a-f]+)/.exec(line);
      m ? resolve(m[1]) : reject(new Error(`unexpected first line: ${line}`));
    });
  });
  const { origin, searchParams } = new URL(url);
  return { child, url, origin, token: searchParams.get('token') };
}

// Installed before the page's scripts: timestamps of every /api/edit and /api/mesh
// request (sent, headers, body received, "applied" = the task after the body, when the
// page's continuation has parsed it and called setMesh).
function instrument() {
  const T = (window.__bench = { edits: [], meshes: [], pointers: [], frames: [], tasks: [], lastMesh: undefined, on: false });
  const realFetch = window.fetch.bind(window);
  // Resource timing of every request (the network side of a round trip), not only 250.
  performance.setResourceTimingBufferSize(1e6);
  // Every animation-frame callback's start and end (the page's renders run in them).
  const raf = (T.raf = window.requestAnimationFrame.bind(window));
  window.requestAnimationFrame = (cb) =>
    raf((ts) => {
      const t0 = performance.now();
      cb(ts);
      if (T.on) T.tasks.push({ kind: 'raf', t0, t1: performance.now() });
    });
  const afterTasks = (fn) => {
    const ch = new MessageChannel();
    ch.port1.onmessage = () => fn();
    ch.port2.postMessage(0);
  };
  // The page reads the mesh with res.arrayBuffer(): time its end, then the task after it.
  const pending = new WeakMap();
  const arrayBuffer = Response.prototype.arrayBuffer;
  Response.prototype.arrayBuffer = async function () {
    const b = await arrayBuffer.call(this);
    const rec = pending.get(this);
    if (rec) {
      rec.body = performance.now();
      rec.bytes = b.byteLength;
      rec.revision = new DataView(b, 8, 4).getUint32(0, true);
      afterTasks(() => (rec.applied = performance.now()));
    }
    return b;
  };
  window.fetch = async (input, init) => {
    const url = typeof input === 'string' ? input : input.url;
    if (!T.on || !(url.startsWith('/api/edit') || url.startsWith('/api/mesh'))) return realFetch(input, init);
    const rec = { sent: performance.now() };
    const res = await realFetch(input, init);
    rec.headers = performance.now();
    if (url.startsWith('/api/edit')) {
      T.edits.push(rec);
      const status = res.headers.get('X-Status');
      if (status === null) {
        res.clone().json().then((s) => (rec.revision = s.revision), () => {});
        return res;
      }
      // An edit that brings its mesh (?mesh=1): the mesh record starts when its headers
      // are in (no second request: "edit answered -> GET /api/mesh sent" and "mesh
      // request -> headers" are 0).
      rec.revision = JSON.parse(status).revision;
      const mesh = { sent: rec.headers, headers: rec.headers };
      T.meshes.push(mesh);
      mesh.solveMs = Number(res.headers.get('X-Solve-Ms'));
      mesh.tessellateMs = Number(res.headers.get('X-Tessellate-Ms'));
      pending.set(res, mesh);
      return res;
    }
    T.meshes.push(rec);
    rec.solveMs = Number(res.headers.get('X-Solve-Ms'));
    rec.tessellateMs = Number(res.headers.get('X-Tessellate-Ms'));
    pending.set(res, rec);
    return res;
  };
}

// Started once the page is ready, so its rAF callback runs after the page's render in
// every frame. A frame where the page's mesh revision changed is "the first frame after
// the mesh was applied" (meshes are applied in fetch continuations, never inside rAF).
function watchFrames() {
  const T = window.__bench;
  const canvas = document.querySelector('[data-testid="frame-view"] canvas');
  canvas.addEventListener('pointermove', (ev) => {
    if (T.on && ev.buttons) T.pointers.push({ t: performance.now(), stamp: ev.timeStamp });
  }, { capture: true });
  const gl = document.querySelector('[data-testid="surface-view"] canvas').getContext('webgl2');
  T.finish = false;
  canvas.addEventListener('pointerup', () => (T.upAt = performance.now()), { capture: true });
  const key = () => { const s = window.__studio.state(); return `${s.mesh}/${s.resolution}`; };
  T.lastMesh = key();
  // Every frame in which a view drew (during releases: T.drawLog on), the surface's draws
  // waited for, whether its boundary-curve overlay was shown.
  T.drawLog = null;
  let seen = window.__studio.draws();
  const loop = (ts) => {
    const d = window.__studio.draws();
    if (T.drawLog && (d.surface !== seen.surface || d.frame !== seen.frame)) {
      const e = { raf: performance.now(), surface: d.surface - seen.surface, frame: d.frame - seen.frame, overlay: d.overlay };
      if (e.surface && gl) {
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        e.drawn = performance.now();
      }
      T.drawLog.push(e);
    }
    seen = d;
    const k = key();
    if (k !== T.lastMesh) {
      const st = window.__studio.state();
      const f = { raf: performance.now(), ts, revision: st.mesh, resolution: st.resolution };
      // Step mode: also the time the GPU (SwiftShader) has drawn it: reading a pixel
      // waits for the draw (gl.finish() does not, in Chromium's GPU process).
      if (T.finish && gl) {
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        f.drawn = performance.now();
      }
      T.frames.push(f);
      T.lastMesh = k;
    }
    T.raf(loop);
  };
  T.raf(loop);
}

const pct = (xs, p) => {
  const s = [...xs].sort((a, b) => a - b);
  if (!s.length) return NaN;
  return s[Math.min(s.length - 1, Math.max(0, Math.ceil((p / 100) * s.length) - 1))];
};
const stats = (xs) => ({ n: xs.length, p50: pct(xs, 50), p95: pct(xs, 95), max: Math.max(...xs), mean: xs.reduce((a, b) => a + b, 0) / xs.length });
const fmt = (s) => `p50 ${s.p50.toFixed(1).padStart(6)}  p95 ${s.p95.toFixed(1).padStart(6)}  max ${s.max.toFixed(1).padStart(6)}  mean ${s.mean.toFixed(1).padStart(6)} ms`;

async function main() {
  const root = mkdtempSync(path.join(tmpdir(), 'pdesurf-bench-studio-'));
  const model = path.join(root, MODEL ? path.basename(MODEL) : 'latency.json');
  if (MODEL) writeFileSync(model, readFileSync(MODEL));
  else execFileSync('python3', [path.join(HERE, 'make_model.py'), model, String(ROWS), String(COLS)], { stdio: 'ignore' });
  const started = await startStudio(model);
  const { child, origin, token } = started;
  const url = `${started.url}${PREVIEW ? '' : '&preview=0'}${QUERY ? `&${QUERY}` : ''}`;
  const browser = await chromium.launch(LAUNCH);
  const loadStart = loadavg();
  const results = { loadStart, model: MODEL ? { file: MODEL } : { rows: ROWS, cols: COLS, frames: ROWS * COLS }, resolution: Number(RESOLUTION), preview: PREVIEW };
  try {
    const page = await browser.newPage({ viewport: { width: 1440, height: 860 } });
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.addInitScript(instrument);
    await page.goto(url);
    await page.waitForSelector('body[data-ready="true"]', { timeout: 60000 });
    await page.getByTestId('resolution').selectOption(RESOLUTION);
    const upToDate = () =>
      page.waitForFunction(() => {
        const s = window.__studio.state();
        return s.mesh === s.revision && s.mesh !== undefined;
      }, null, { timeout: 60000, polling: 'raf' });
    await page.waitForFunction((r) => {
      const m = document.querySelector('[data-testid="status"]').textContent;
      return /triangles/.test(m);
    }, RESOLUTION);
    await page.waitForTimeout(500);
    await page.evaluate(watchFrames);
    results.idleFrame = await page.evaluate(() => new Promise((resolve) => {
      const ts = [];
      const tick = (t) => { ts.push(t); if (ts.length < 21) requestAnimationFrame(tick); else resolve(ts.slice(1).map((x, i) => x - ts[i])); };
      requestAnimationFrame(tick);
    })).then((d) => stats(d));
    console.error(`idle frame interval: ${fmt(results.idleFrame)}`);
    // One draw of each view, waited for (render, then read a pixel back), at rest.
    const draws = await page.evaluate(() => window.__studio.renderTimes(7));
    results.draw = { frameView: stats(draws.frames), surfaceView: stats(draws.surface) };

    // A vertex in the middle of the sheet, on screen in the frame view.
    const lattice = { i: ROWS, j: 2 * Math.floor(COLS / 2) }; // an even-even lattice point
    const vertex = await page.evaluate(({ i, j }) => {
      // vertex index of lattice point (i, j): rows of 2*COLS+1 (even i) or COLS+1 (odd i) points
      return null;
    }, lattice);
    void vertex;
    const state = await (await fetch(`${origin}/api/model`, { headers: { 'X-Pdesurf-Token': token } })).json();
    const vs = state.model.vertices;
    results.model.frames = state.model.frames.length;
    const cx = (COLS * 0.5), cy = (ROWS * 0.5);
    let best = 0;
    if (MODEL) {
      // The handle nearest the frame view's centre on screen.
      best = await page.evaluate((n) => {
        const r = document.querySelector('[data-testid="frame-view"] canvas').getBoundingClientRect();
        let k = 0, d = Infinity;
        for (let i = 0; i < n; ++i) {
          const q = window.__studio.vertexScreen(i);
          const di = Math.hypot(q.x - (r.left + r.width / 2), q.y - (r.top + r.height / 2));
          if (di < d) (d = di), (k = i);
        }
        return k;
      }, vs.length);
    } else {
      vs.forEach((v, k) => {
        if (Math.hypot(v[0] - cx, v[1] - cy) < Math.hypot(vs[best][0] - cx, vs[best][1] - cy)) best = k;
      });
    }
    const p = await page.evaluate((k) => window.__studio.vertexScreen(k), best);
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    const picked = await page.getByTestId('vertex-index').textContent();
    if (picked !== `#${best}`) throw new Error(`pressed at vertex ${best}'s handle, the page selected ${picked}`);
    results.vertex = best;

    // Run 1: one edit at a time.
    const offsets = (k) => ({ x: p.x + 6 * Math.sin(k * 0.7), y: p.y - 6 - 6 * Math.cos(k * 0.5) });
    for (let k = 0; k < 5; ++k) { await page.mouse.move(offsets(k).x, offsets(k).y); await upToDate(); } // warm-up
    await page.evaluate(() => { Object.assign(window.__bench, { on: true, finish: true, edits: [], meshes: [], pointers: [], frames: [] }); });
    const steps = [];
    for (let k = 0; k < STEPS; ++k) {
      await page.evaluate(() => { const T = window.__bench; T.edits = []; T.meshes = []; T.pointers = []; T.frames = []; T.tasks = []; });
      const q = offsets(k + 5);
      await page.mouse.move(q.x, q.y);
      await upToDate();
      // The records of this step's edit: its mesh (by revision) applied, and the first
      // frame that showed that revision.
      const r = await page.evaluate(() => new Promise((resolve) => {
        const T = window.__bench;
        const check = () => {
          const e = T.edits[T.edits.length - 1];
          const m = e && T.meshes.find((x) => x.revision === e.revision);
          const f = e && T.frames.find((x) => x.revision === e.revision);
          // The network side of the edit's round trip (resource timing), and the page's
          // animation-frame callbacks from the pointer event to the answer's headers.
          const net = e && performance.getEntriesByType('resource').filter((x) => x.name.includes('/api/edit')).pop();
          if (m && m.applied !== undefined && f && net) {
            performance.clearResourceTimings();
            const rt = { start: net.startTime, request: net.requestStart, response: net.responseStart, end: net.responseEnd };
            resolve({ pointers: T.pointers, edits: T.edits, m, f, rt, tasks: T.tasks });
          } else T.raf(check);
        };
        check();
      }));
      if (process.env.BENCH_DEBUG) console.error(JSON.stringify(r));
      if (r.pointers.length !== 1 || r.edits.length !== 1) {
        steps.push({ skipped: true, counts: [r.pointers.length, r.edits.length] });
      } else {
        const [pt, e, m, f, rt] = [r.pointers[0], r.edits[0], r.m, r.f, r.rt];
        // Main-thread time in animation-frame callbacks (the page's renders) while the
        // edit was in flight.
        const busy = r.tasks.reduce((sum, t) => sum + Math.max(0, Math.min(t.t1, e.headers) - Math.max(t.t0, e.sent)), 0);
        steps.push({
          toRequest: rt.request - e.sent, serverWait: rt.response - rt.request, toHeaders: e.headers - rt.response,
          rafBusy: busy,
          total: f.raf - pt.t, fromStamp: f.raf - pt.stamp, drawn: f.drawn - pt.t,
          toEdit: e.sent - pt.t, editRtt: e.headers - e.sent, toMesh: m.sent - e.headers,
          meshWait: m.headers - m.sent, meshBody: m.body - m.headers, apply: m.applied - m.body,
          bodyToFrame: f.raf - m.body, toFrame: f.raf - m.applied, gpu: f.drawn - f.raf,
          solveMs: m.solveMs, tessellateMs: m.tessellateMs, bytes: m.bytes,
        });
      }
      if (process.env.BENCH_STEPS_FILE) appendFileSync(process.env.BENCH_STEPS_FILE, JSON.stringify(steps[steps.length - 1]) + '\n');
      if (process.stderr.isTTY || process.env.BENCH_PROGRESS) process.stderr.write(`\rstep ${k + 1}/${STEPS}`);
      await page.waitForTimeout(50);
    }
    const ok = steps.filter((s) => !s.skipped);
    const col = (k) => ok.map((s) => s[k]);
    results.step = { steps: STEPS, timed: ok.length, skipped: steps.length - ok.length };
    for (const k of ['total', 'fromStamp', 'drawn', 'toEdit', 'editRtt', 'toRequest', 'serverWait', 'toHeaders', 'rafBusy', 'toMesh', 'meshWait', 'meshBody', 'bodyToFrame', 'apply', 'toFrame', 'gpu', 'solveMs', 'tessellateMs'])
      results.step[k] = stats(col(k));
    results.step.meshBytes = ok.length ? ok[0].bytes : 0;

    // Run 2: a 60 Hz drag.
    if (STREAM > 0) {
    await page.evaluate(() => Object.assign(window.__bench, { finish: false, edits: [], meshes: [], pointers: [], frames: [] }));
    const t0 = Date.now();
    for (let k = 0; k < STREAM; ++k) {
      const q = offsets(k + STEPS + 5);
      await page.mouse.move(q.x, q.y);
      const next = t0 + (k + 1) * (1000 / 60);
      const wait = next - Date.now();
      if (wait > 0) await new Promise((r) => setTimeout(r, wait));
    }
    const streamSeconds = (Date.now() - t0) / 1000;
    await page.evaluate(() => window.__studio.idle());
    await upToDate();
    await page.waitForTimeout(200);
    const s = await page.evaluate(() => {
      const T = window.__bench;
      return { pointers: T.pointers, edits: T.edits, meshes: T.meshes, frames: T.frames };
    });
    // Each pointer event rides on the first edit sent after it; it is shown by the first
    // frame whose mesh revision is at or past that edit's.
    const lat = [];
    for (const pt of s.pointers) {
      const e = s.edits.find((x) => x.sent >= pt.t);
      if (!e || e.revision === undefined) continue;
      const f = s.frames.find((x) => x.raf >= e.sent && x.revision >= e.revision);
      if (f) lat.push(f.raf - pt.t);
    }
    results.stream = {
      pointerEvents: s.pointers.length, seconds: streamSeconds, edits: s.edits.length, meshes: s.meshes.length,
      newFrames: s.frames.length, meshesPerSecond: s.frames.length / streamSeconds, latency: stats(lat),
    };
    }
    await page.mouse.up();
    // Releases: a short drag, then the button's release to the first frame drawn at the
    // full resolution (the preview's end).
    const full = Number(RESOLUTION);
    const releases = [];
    const releaseSplits = [];
    for (let k = 0; k < RELEASES; ++k) {
      await page.evaluate(() => window.__studio.idle());
      await upToDate();
      await page.waitForFunction((r) => window.__studio.state().resolution === r, full, { timeout: 60000 });
      const h = await page.evaluate((v) => window.__studio.vertexScreen(v), best);
      await page.mouse.move(h.x, h.y);
      await page.mouse.down();
      for (let j = 1; j <= 3; ++j) { await page.mouse.move(h.x + 3 * j, h.y - 2 * j); await upToDate(); }
      await page.evaluate(() => Object.assign(window.__bench, { finish: true, frames: [], meshes: [], upAt: undefined, drawLog: [] }));
      // Without a preview the surface is at full resolution already: nothing to wait for.
      const previewed = await page.evaluate((r) => window.__studio.state().resolution !== r, full);
      await page.mouse.up();
      const ms = !previewed ? 0 : await page.evaluate((r) => new Promise((resolve) => {
        const T = window.__bench;
        const check = () => {
          const f = T.upAt !== undefined && T.frames.find((x) => x.raf >= T.upAt && x.resolution === r);
          if (f) resolve(f.drawn - T.upAt);
          else requestAnimationFrame(check);
        };
        check();
      }), full);
      releases.push(ms);
      // What the release drew until the views settled (no draw for SETTLE_MS): each view's
      // draws, the last surface draw done, the overlay then; the full mesh's request.
      const after = await page.evaluate(({ settle, r }) => new Promise((resolve) => {
        const T = window.__bench;
        const check = () => {
          const last = T.drawLog.length ? T.drawLog[T.drawLog.length - 1].raf : T.upAt;
          if (performance.now() - last < settle) { requestAnimationFrame(check); return; }
          const log = T.drawLog.filter((e) => e.raf >= T.upAt);
          T.drawLog = null;
          const surface = log.filter((e) => e.surface);
          const lastSurface = surface[surface.length - 1];
          const m = T.meshes.filter((x) => x.sent >= T.upAt && x.revision !== undefined).pop();
          const f = T.frames.find((x) => x.raf >= T.upAt && x.resolution === r);
          resolve({
            surfaceDraws: surface.reduce((n, e) => n + e.surface, 0),
            frameDraws: log.reduce((n, e) => n + e.frame, 0),
            settled: lastSurface ? lastSurface.drawn - T.upAt : 0,
            overlay: lastSurface ? lastSurface.overlay : undefined,
            toMesh: m ? m.sent - T.upAt : NaN,
            meshWait: m ? m.headers - m.sent : NaN,
            meshBody: m ? m.body - m.headers : NaN,
            bytes: m ? m.bytes : NaN,
            tessellateMs: m ? m.tessellateMs : NaN,
            toFrame: m && f ? f.raf - m.body : NaN,
            gpu: f ? f.drawn - f.raf : NaN,
          });
        };
        check();
      }), { settle: SETTLE_MS, r: full });
      if (process.env.BENCH_DEBUG) console.error(JSON.stringify({ release: ms, ...after }));
      releaseSplits.push(after);
    }
    if (RELEASES > 0) {
      results.release = stats(releases);
      for (const k of ['surfaceDraws', 'frameDraws', 'settled', 'toMesh', 'meshWait', 'meshBody', 'toFrame', 'gpu', 'tessellateMs', 'bytes'])
        results.release[k] = stats(releaseSplits.map((x) => x[k]));
      results.release.overlayShown = releaseSplits.filter((x) => x.overlay).length;
    }
    if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
  } finally {
    await browser.close();
    child.kill('SIGTERM');
    rmSync(root, { recursive: true, force: true });
  }

  const st = results.step;
  console.log(`Studio edit-to-new-frame latency: ${MODEL || `${ROWS}x${COLS} sheet`}, ${results.model.frames} frames, Res ${RESOLUTION}, ` +
    `preview ${PREVIEW ? 'on' : 'off'}, mesh ${(st.meshBytes / 1e6).toFixed(2)} MB, chromium (SwiftShader), ${cpus().length} cores`);
  console.log(`\nOne edit at a time (${st.timed} of ${st.steps} steps timed):`);
  console.log(`  pointer event -> first rAF with the new mesh   ${fmt(st.total)}`);
  console.log(`  (from the event's timeStamp)                   ${fmt(st.fromStamp)}`);
  console.log(`  pointer event -> drawn (gl.finish)             ${fmt(st.drawn)}`);
  console.log('  split (medians, p95):');
  const row = (label, k) => console.log(`    ${label.padEnd(44)} ${st[k].p50.toFixed(2).padStart(7)} ${st[k].p95.toFixed(2).padStart(7)} ms`);
  row('pointer -> POST /api/edit sent', 'toEdit');
  row('edit round trip (with the mesh, ?mesh=1)', 'editRtt');
  row('  fetch() -> request sent (resource timing)', 'toRequest');
  row('  request sent -> response starts (server)', 'serverWait');
  row('  response starts -> page has the headers', 'toHeaders');
  row('  page rAF callbacks (renders) meanwhile', 'rafBusy');
  row('edit answered -> GET /api/mesh sent', 'toMesh');
  row('mesh request -> headers (server solve+tess)', 'meshWait');
  row('  of which X-Solve-Ms', 'solveMs');
  row('  of which X-Tessellate-Ms', 'tessellateMs');
  row('mesh body transfer', 'meshBody');
  row('body read -> first rAF with it (parse, setMesh)', 'bodyToFrame');
  row('rAF -> drawn (gl.finish)', 'gpu');
  console.log(`  one draw at rest, waited for (renderTimes): frame view ${fmt(results.draw.frameView)}`);
  console.log(`                                            surface view ${fmt(results.draw.surfaceView)}`);
  const sm = results.stream;
  if (sm) console.log(`\n60 Hz drag (${sm.pointerEvents} pointer events in ${sm.seconds.toFixed(1)} s, ${sm.edits} edits, ` +
    `${sm.newFrames} new surface frames = ${sm.meshesPerSecond.toFixed(1)}/s):`);
  if (sm) console.log(`  pointer event -> first rAF showing it          ${fmt(sm.latency)}`);
  const rl = results.release;
  if (rl) {
    console.log(`\nRelease -> first frame drawn at Res ${RESOLUTION} (${rl.n} drags): ${fmt(rl)}`);
    console.log('  split (medians, p95):');
    const rrow = (label, k, unit = 'ms') => console.log(`    ${label.padEnd(44)} ${rl[k].p50.toFixed(2).padStart(9)} ${rl[k].p95.toFixed(2).padStart(9)} ${unit}`);
    rrow('release -> full-resolution mesh asked', 'toMesh');
    rrow('mesh request -> headers', 'meshWait');
    rrow('  of which X-Tessellate-Ms', 'tessellateMs');
    rrow('mesh body read', 'meshBody');
    rrow('mesh bytes', 'bytes', 'B');
    rrow('body read -> first rAF with it', 'toFrame');
    rrow('rAF -> drawn (readPixels)', 'gpu');
    rrow('surface view draws after the release', 'surfaceDraws', '');
    rrow('frame view draws after the release', 'frameDraws', '');
    rrow('release -> last surface draw done (settled)', 'settled');
    console.log(`    boundary overlay shown at the last draw: ${rl.overlayShown} of ${rl.n}`);
  }
  console.log(`\nLoad average (1, 5, 15 min) at the start: ${results.loadStart.map((x) => x.toFixed(2)).join(', ')}; at the end: ${loadavg().map((x) => x.toFixed(2)).join(', ')}`);
  console.log(`\nIdle page: one frame every ${results.idleFrame.p50.toFixed(1)} ms (p50 rAF interval, nothing changing)`);
  const met = st.total.p95 <= 16;
  console.log(`\nTarget p95 <= 16 ms (one edit at a time): ${met ? 'MET' : 'NOT MET'} (p95 ${st.total.p95.toFixed(1)} ms)`);
  if (JSON_OUT) writeFileSync(JSON_OUT, JSON.stringify(results, null, 2));
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
