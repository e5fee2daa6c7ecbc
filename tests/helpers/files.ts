/**
 * Temp dirs and logs of the throwaway services: where they live, how they are swept, and how
 * logs are kept (copied to test-results/services/) when a test fails.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** The repository root (tests/helpers/../..), whatever the cwd. */
export const REPO_ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
/** Where kept service logs go. */
export const KEPT_LOGS_DIR = path.join(REPO_ROOT, 'test-results', 'services');

const OWNER_FILE = '.owner-pid';
let swept = false;

/** Removes temp dirs left by test processes that were SIGKILLed (their owner pid is gone). */
function sweepStaleDirs(): void {
  swept = true;
  for (const entry of fs.readdirSync(os.tmpdir())) {
    if (!/^armtwin-(mosquitto|influxd)-/.test(entry)) continue;
    const dir = path.join(os.tmpdir(), entry);
    try {
      process.kill(Number(fs.readFileSync(path.join(dir, OWNER_FILE), 'utf8')), 0);
    } catch (err) {
      if ((err as NodeJS.ErrnoException).code === 'ESRCH')
        fs.rmSync(dir, { recursive: true, force: true });
    }
  }
}

/** Makes a fresh temp dir `/tmp/armtwin-<name>-XXXXXX`, marked with our pid. */
export function makeTempDir(name: string): string {
  if (!swept) sweepStaleDirs();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), `armtwin-${name}-`));
  fs.writeFileSync(path.join(dir, OWNER_FILE), String(process.pid));
  return dir;
}

/** The last `lines` lines of a file ('' if it does not exist). */
export function tail(file: string, lines = 30): string {
  try {
    return fs.readFileSync(file, 'utf8').trimEnd().split('\n').slice(-lines).join('\n');
  } catch {
    return '';
  }
}

/** Copies `*.log` and `*.conf` from dir to test-results/services/<name>-<timestamp>/; returns it. */
export function keepLogs(dir: string, name: string): string {
  const stamp = new Date().toISOString().replace(/[:.]/g, '-');
  const target = path.join(KEPT_LOGS_DIR, `${name}-${stamp}-${process.pid}`);
  fs.mkdirSync(target, { recursive: true });
  for (const entry of fs.readdirSync(dir)) {
    if (/\.(log|conf)$/.test(entry))
      fs.copyFileSync(path.join(dir, entry), path.join(target, entry));
  }
  return target;
}

const liveDirs = new Set<string>(); // temp dirs of services not yet disposed

/** Marks a temp dir as in use: removed by removeTrackedDirs() if never removed otherwise. */
export function trackDir(dir: string): void {
  liveDirs.add(dir);
}

/** Removes a temp dir and forgets it. */
export function removeDir(dir: string): void {
  fs.rmSync(dir, { recursive: true, force: true });
  liveDirs.delete(dir);
}

/** Removes every tracked temp dir (synchronous: runs in an `exit` handler). */
export function removeTrackedDirs(): void {
  for (const dir of liveDirs) fs.rmSync(dir, { recursive: true, force: true });
  liveDirs.clear();
}
