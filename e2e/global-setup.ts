// Fails early, with the fix, when what the tests need is missing.
import { existsSync } from 'node:fs';
import path from 'node:path';

export default function globalSetup(): void {
  const source = path.resolve(__dirname, '..');
  const cli = process.env.PDESURF_CLI || path.join(source, 'build', 'pdesurf');
  const chromium = process.env.PDESURF_CHROMIUM || '/usr/bin/chromium';
  const web = process.env.PDESURF_WEB_DIR || path.join(source, 'web', 'dist');
  const missing: string[] = [];
  if (!existsSync(cli)) missing.push(`${cli} (run \`make build\`)`);
  if (!existsSync(path.join(web, 'index.html'))) missing.push(`${web}/index.html (run \`make build\`)`);
  if (!existsSync(chromium)) missing.push(`${chromium} (run \`scripts/setup\`: apt-get install chromium)`);
  if (missing.length) throw new Error(`e2e: missing ${missing.join(', ')}`);
}
