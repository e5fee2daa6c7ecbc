/**
 * Rewriting a robot's `profile.json` on disk: the old file is kept beside it as a dated backup
 * (`profile.json.<UTC time>.bak`), and the new one is written to a temporary file in the same
 * folder and renamed over the old, so a reader (the bus gateway watching it, the HUD fetching
 * it) sees the old file or the new one, never half of one.
 */
import fs from 'node:fs';
import path from 'node:path';

/** `2026-11-24T06-01-32-123Z`: a file-name-safe UTC time. */
const stamp = (d: Date) => d.toISOString().replaceAll(':', '-').replace('.', '-');

/** Writes `json` as `file` (2-space JSON and a newline); returns the backup's file name. */
export function replaceProfileFile(file: string, json: unknown, now = new Date()): string {
  const dir = path.dirname(file);
  const backup = `${path.basename(file)}.${stamp(now)}.bak`;
  fs.copyFileSync(file, path.join(dir, backup));
  const tmp = path.join(dir, `.${path.basename(file)}.${process.pid}.tmp`);
  try {
    fs.writeFileSync(tmp, `${JSON.stringify(json, null, 2)}\n`);
    fs.renameSync(tmp, file);
  } catch (err) {
    fs.rmSync(tmp, { force: true });
    throw err;
  }
  return backup;
}
