/**
 * The Python 3.12 venv of the SO-101/LeRobot tests (`scripts/pyenv-lerobot.sh`, run by
 * install-deps.sh): PyPI's `lerobot` 0.6.1, `example-robot-data` (the SO-100/SO-101
 * descriptions) and `yourdfpy` (an FK that is not armtwin's), cached beside the servo-SDK venv.
 * Missing is an error, not a skip: these are how the SO-101 support is proved.
 */
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from './services.ts';
import { armtwinCacheDir } from '@armtwin/ros2';

export const lerobotVenv = (env: NodeJS.ProcessEnv = process.env): string =>
  path.join(armtwinCacheDir(env), 'pyenv-lerobot');

/** The Python scripts the tests run in that venv. */
export const LEROBOT_SCRIPTS = path.join(REPO_ROOT, 'tests', 'helpers', 'lerobot');

/** The venv's python, checked to import `modules`; throws with what to run when it cannot. */
export function lerobotPython(
  modules = 'lerobot, yourdfpy',
  env: NodeJS.ProcessEnv = process.env,
): string {
  const python = path.join(lerobotVenv(env), 'bin', 'python');
  const fix =
    'run `bash scripts/install-deps.sh` (it creates the venv with scripts/pyenv-lerobot.sh)';
  if (!fs.existsSync(python)) throw new Error(`no LeRobot venv at ${lerobotVenv(env)}: ${fix}`);
  try {
    execFileSync(python, ['-c', `import ${modules}`], { stdio: 'pipe' });
  } catch (err) {
    const detail =
      (err as { stderr?: Buffer }).stderr?.toString().trim().split('\n').at(-1) ?? String(err);
    throw new Error(`${python} cannot import ${modules} (${detail}): ${fix}`, { cause: err });
  }
  return python;
}

/** Runs `script` (in tests/helpers/lerobot) with `input` as JSON on stdin; its stdout's JSON. */
export function runLerobotScript<T>(script: string, input: unknown, modules?: string): T {
  const out = execFileSync(lerobotPython(modules), [path.join(LEROBOT_SCRIPTS, script)], {
    input: JSON.stringify(input),
    stdio: ['pipe', 'pipe', 'pipe'],
    maxBuffer: 64 * 1024 * 1024,
  });
  return JSON.parse(out.toString()) as T;
}

/** armtwin's LeRobot plugin in this clone (packages/lerobot/python). */
export const PLUGIN_DIR = path.join(REPO_ROOT, 'packages', 'lerobot', 'python');

export interface PluginScript {
  /** What it printed so far. */
  out(): string;
  err(): string;
  /** It has exited. */
  ended(): boolean;
  /** Its exit code. */
  exited: Promise<number | null>;
}

/**
 * Starts `script` (in tests/helpers/lerobot) in the venv with `input` as JSON on stdin. LeRobot
 * finds the installed plugin distribution (scripts/pyenv-lerobot.sh); its module is imported
 * from this clone's sources, first on the path.
 */
export function startPluginScript(script: string, input: unknown): PluginScript {
  const py = spawn(
    lerobotPython('lerobot, lerobot_robot_armtwin'),
    [path.join(LEROBOT_SCRIPTS, script)],
    { env: { ...process.env, PYTHONPATH: PLUGIN_DIR } },
  );
  let out = '';
  let err = '';
  let ended = false;
  py.stdout.on('data', (d: Buffer) => (out += d.toString()));
  py.stderr.on('data', (d: Buffer) => (err += d.toString()));
  const exited = new Promise<number | null>((r) => py.once('exit', r)).finally(
    () => (ended = true),
  );
  py.stdin.end(JSON.stringify(input));
  return { out: () => out, err: () => err, ended: () => ended, exited };
}
