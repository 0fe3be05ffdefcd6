import { defineConfig } from 'vitest/config';

// The page's unit tests (web/test): the logic that is not drawing (the mesh wire format,
// the edit pump, mesh sync, number input, the store), in Node.
export default defineConfig({
  test: { include: ['test/**/*.test.ts'], environment: 'node' },
});
