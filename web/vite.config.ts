import { defineConfig } from 'vite';

// The studio server serves dist/ at its root; during `npm run dev` the API is proxied to a
// running `pdesurf studio --port 8080`.
export default defineConfig({
  base: '/',
  build: { outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1024 },
  server: { proxy: { '/api': 'http://127.0.0.1:8080' } },
});
