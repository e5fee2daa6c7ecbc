/**
 * Child processes of the benchmark and their CPU time. Every child is started through
 * `spawnChild`: it runs under `setpriv --pdeathsig KILL` where available (so the kernel kills
 * it if the benchmark dies), is remembered, and `killAll()` (also run on exit and on
 * SIGINT/SIGTERM) kills whatever is still alive, by pid. CPU time is read from
 * /proc/<pid>/stat (utime + stime, in clock ticks).
 */
import { execFileSync, spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';

const SETPRIV = '/usr/bin/setpriv';
const live = new Set<ChildProcess>();
let handlers = false;

/** Clock ticks per second (`getconf CLK_TCK`, 100 on Linux unless told otherwise). */
export const CLK_TCK = (() => {
  try {
    return Number(execFileSync('getconf', ['CLK_TCK'], { encoding: 'utf8' }).trim()) || 100;
  } catch {
    return 100;
  }
})();

/** User + system CPU seconds the process has used so far (NaN if it is gone). */
export function cpuSeconds(pid: number): number {
  try {
    const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
    // Fields after the ")" that closes the command name: state is index 0, utime 11, stime 12.
    const f = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    return (Number(f[11]) + Number(f[12])) / CLK_TCK;
  } catch {
    return NaN;
  }
}

/** A CPU meter over a window: `start()` then `stop()` → CPU seconds and wall seconds. */
export function cpuMeter(pid: number) {
  let c0 = NaN;
  let w0 = 0n;
  return {
    start() {
      c0 = cpuSeconds(pid);
      w0 = process.hrtime.bigint();
    },
    stop(): { cpuS: number; wallS: number; share: number } {
      const cpuS = cpuSeconds(pid) - c0;
      const wallS = Number(process.hrtime.bigint() - w0) / 1e9;
      return { cpuS, wallS, share: cpuS / wallS };
    },
  };
}

function installHandlers(): void {
  if (handlers) return;
  handlers = true;
  process.on('exit', killAll);
  for (const sig of ['SIGINT', 'SIGTERM', 'SIGHUP'] as const) {
    process.once(sig, () => {
      killAll();
      process.exit(130);
    });
  }
}

export interface Child {
  proc: ChildProcess;
  pid: number;
  exited: Promise<number | null>;
  /** SIGTERM, then SIGKILL after graceMs; resolves when it has exited. */
  stop(graceMs?: number): Promise<void>;
}

/** Spawns a tracked child; stdout/stderr go to `logFile` (or are ignored). */
export function spawnChild(
  command: string,
  args: string[],
  opts: { env?: NodeJS.ProcessEnv; cwd?: string; logFile?: string; stdout?: 'pipe' } = {},
): Child {
  installHandlers();
  const fd = opts.logFile ? fs.openSync(opts.logFile, 'a') : 'ignore';
  const [file, argv] = fs.existsSync(SETPRIV)
    ? [SETPRIV, ['--pdeathsig', 'KILL', '--', command, ...args]]
    : [command, args];
  const proc = spawn(file, argv, {
    cwd: opts.cwd,
    env: opts.env ?? process.env,
    stdio: ['ignore', opts.stdout ?? fd, fd],
  });
  if (typeof fd === 'number') fs.closeSync(fd);
  live.add(proc);
  const exited = new Promise<number | null>((resolve) => {
    proc.once('exit', (code) => {
      live.delete(proc);
      resolve(code);
    });
    proc.once('error', () => {
      live.delete(proc);
      resolve(null);
    });
  });
  return {
    proc,
    pid: proc.pid ?? -1,
    exited,
    async stop(graceMs = 5000) {
      if (proc.exitCode !== null || proc.signalCode !== null) return;
      proc.kill('SIGTERM');
      const t = setTimeout(() => proc.kill('SIGKILL'), graceMs);
      await exited;
      clearTimeout(t);
    },
  };
}

/** SIGKILLs every tracked child still alive (each by its own pid). */
export function killAll(): void {
  for (const p of live) {
    try {
      p.kill('SIGKILL');
    } catch {
      // already gone
    }
  }
  live.clear();
}

/** How many tracked children are still alive (the orchestrator checks 0 at the end). */
export function liveChildren(): number {
  return live.size;
}

export const sleep = (ms: number) => new Promise<void>((r) => setTimeout(r, ms));

/** Polls `fn` every `everyMs` until it returns true or `timeoutMs` passes; returns the last result. */
export async function until(
  fn: () => boolean | Promise<boolean>,
  timeoutMs: number,
  everyMs = 50,
): Promise<boolean> {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    if (await fn()) return true;
    if (Date.now() > deadline) return false;
    await sleep(everyMs);
  }
}

/** The pid of the process whose command line contains `needle` (e.g. a config file path). */
export function findPid(needle: string): number | undefined {
  for (const d of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    try {
      const cmd = fs.readFileSync(`/proc/${d}/cmdline`, 'utf8').replace(/\0/g, ' ');
      if (cmd.includes(needle) && !cmd.startsWith('/usr/bin/setpriv')) return Number(d);
    } catch {
      // gone
    }
  }
  return undefined;
}

/** The pids of `pid`'s live descendants (children, grandchildren …), from /proc/<pid>/stat ppids. */
export function descendants(pid: number): number[] {
  const parent = new Map<number, number>();
  for (const d of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    try {
      const stat = fs.readFileSync(`/proc/${d}/stat`, 'utf8');
      // After the ")" that closes the command name: state, then ppid.
      parent.set(Number(d), Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]));
    } catch {
      // gone
    }
  }
  const out: number[] = [];
  const todo = [pid];
  while (todo.length) {
    const p = todo.pop()!;
    for (const [child, pp] of parent) {
      if (pp !== p) continue;
      out.push(child);
      todo.push(child);
    }
  }
  return out;
}
