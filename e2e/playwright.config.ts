// Browser tests of the studio. The browser is Debian's chromium (apt), never a download:
// PDESURF_CHROMIUM overrides /usr/bin/chromium. Each test starts its own `pdesurf studio`
// (PDESURF_CLI, default ../build/pdesurf) on a temporary copy of an example.
import { defineConfig } from '@playwright/test';
import { cpus } from 'node:os';

export default defineConfig({
  testDir: './tests',
  globalSetup: './global-setup.ts',
  outputDir: './artifacts/test-results',
  timeout: 60_000,
  expect: { timeout: 10_000 },
  fullyParallel: true,
  // Each worker runs a chromium with software WebGL: at most one per core, at most 3.
  workers: Number(process.env.PDESURF_E2E_WORKERS) || Math.max(1, Math.min(3, cpus().length)),
  // One retry in CI: the browser renders in software there, and a timing flake should not
  // hide the other results; a test that fails twice fails.
  retries: process.env.CI ? 1 : 0,
  reporter: [['list']],
  use: {
    viewport: { width: 1440, height: 860 },
    screenshot: 'only-on-failure',
    trace: 'off',
    launchOptions: {
      executablePath: process.env.PDESURF_CHROMIUM || '/usr/bin/chromium',
      args: [
        '--headless',
        '--no-sandbox',
        '--disable-gpu',
        '--disable-quic',
        '--no-first-run',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
        // WebGL without a GPU: the software renderer.
        '--use-angle=swiftshader',
        '--enable-unsafe-swiftshader',
      ],
    },
  },
});
