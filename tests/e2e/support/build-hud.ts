/**
 * Makes sure apps/web/dist is a build of the current sources: builds it when it is missing or
 * older than any file under apps/web/src, apps/web/index.html or public/models.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from '../../helpers/services.ts';

export const HUD_DIST = path.join(REPO_ROOT, 'apps/web/dist');

function newestMtime(p: string): number {
  const st = fs.statSync(p);
  if (!st.isDirectory()) return st.mtimeMs;
  let newest = st.mtimeMs;
  for (const name of fs.readdirSync(p)) newest = Math.max(newest, newestMtime(path.join(p, name)));
  return newest;
}

export function ensureHudBuilt(): void {
  const index = path.join(HUD_DIST, 'index.html');
  const sources = [
    'apps/web/src',
    'apps/web/index.html',
    'apps/web/vite.config.ts',
    'public/models',
  ].map((p) => path.join(REPO_ROOT, p));
  const built = fs.existsSync(index) ? fs.statSync(index).mtimeMs : 0;
  if (built > Math.max(...sources.map(newestMtime))) return;
  execFileSync('npm', ['run', 'build', '-w', '@armtwin/web'], { cwd: REPO_ROOT, stdio: 'inherit' });
}
