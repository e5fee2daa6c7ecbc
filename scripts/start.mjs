#!/usr/bin/env node
// `npm start`: the one command that runs the twin. On a fresh clone it installs the
// dependencies first (`npm ci`), then runs `armtwin up` in this process (TypeScript via tsx):
// the embedded broker, the HUD + /mqtt + /api on ARMTWIN_PORT (default 8080), the simulated
// arm1, the SO-101 on an emulated Feetech bus behind the bus gateway (`so101`; --no-so101 leaves
// it out), the middleware. Extra arguments go to `armtwin up` (npm start -- --rate 250).
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

if (!fs.existsSync(path.join(root, 'node_modules', 'tsx'))) {
  process.stderr.write('armtwin: node_modules is missing; running npm ci first…\n');
  const npm = process.platform === 'win32' ? 'npm.cmd' : 'npm';
  const r = spawnSync(npm, ['ci'], { cwd: root, stdio: 'inherit' });
  if (r.status !== 0) {
    process.stderr.write('armtwin: npm ci failed; fix the error above and run npm start again\n');
    process.exit(r.status ?? 1);
  }
}

const { register } = await import('tsx/esm/api');
register();
const { main } = await import(pathToFileURL(path.join(root, 'apps', 'cli', 'src', 'main.ts')).href);
await main([process.argv[0], 'armtwin', 'up', ...process.argv.slice(2)]);
