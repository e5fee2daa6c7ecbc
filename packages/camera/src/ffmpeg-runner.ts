/**
 * Keeps one ffmpeg running: spawns it with its outputs on pipes, says why it stopped (its exit
 * status and the last line it wrote on stderr), and starts it again after a back-off that grows
 * while it keeps failing. A source that stops sending frames (`stallMs`) gets ffmpeg killed and
 * restarted too. No ffmpeg outlives this process: `stop()` ends it (SIGTERM, then SIGKILL), a
 * process exit kills whatever is left, and if this process is killed outright ffmpeg dies at its
 * next write to the closed pipe.
 */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { backoffDelay, type Backoff } from '@armtwin/protocol';

/** Restart delays (`backoffDelay`); a run of `healthyMs` with frames resets them to `minMs`. */
export interface BackoffOptions extends Backoff {
  healthyMs: number;
}

export const DEFAULT_BACKOFF: BackoffOptions = {
  minMs: 500,
  maxMs: 10_000,
  factor: 2,
  healthyMs: 10_000,
};

export interface FfmpegExit {
  code: number | null;
  signal: NodeJS.Signals | null;
  /** Why, in words: the last stderr line, or what happened. */
  reason: string;
  ranMs: number;
}

export const RUNNER_EVENTS = ['exit', 'spawn-failed', 'stall'] as const;
export type RunnerEvent = (typeof RUNNER_EVENTS)[number];

export interface FfmpegRunnerOptions {
  /** The ffmpeg program. */
  command: string;
  args: readonly string[];
  /** Output pipes: child file descriptor (1, 3, …) → what reads it. */
  outputs: Record<number, (chunk: Buffer) => void>;
  backoff: BackoffOptions;
  /** No frame for this long (`frame()` not called) → ffmpeg is restarted, ms; 0 = never. */
  stallMs: number;
  /** Called before each (re)start, so the readers can start a new stream. */
  onStart: () => void;
  /** Called each time ffmpeg ends, before the restart is scheduled. */
  onExit: (exit: FfmpegExit, restartInMs: number | null) => void;
  onEvent: (event: RunnerEvent, message: string) => void;
  now: () => number;
}

export interface FfmpegRunnerStats {
  running: boolean;
  pid: number | null;
  starts: number;
  restarts: number;
  events: Record<RunnerEvent, number>;
  lastExit: FfmpegExit | null;
  /** When the next start is due (epoch ms), while waiting. */
  restartAt: number | null;
}

const live = new Set<ChildProcess>();
let exitHookInstalled = false;
function killLiveChildren(): void {
  for (const child of live) child.kill('SIGKILL');
  live.clear();
}

/** Bytes of stderr kept for the last line. */
const STDERR_TAIL = 4096;
const KILL_AFTER_MS = 2000;

export class FfmpegRunner {
  private child: ChildProcess | null = null;
  private stopped = true;
  private startedAt = 0;
  private lastFrameAt = 0;
  private sawFrame = false;
  private failures = 0;
  private stderrTail = '';
  private restartTimer: ReturnType<typeof setTimeout> | null = null;
  private stallTimer: ReturnType<typeof setInterval> | null = null;
  private exited: Promise<void> = Promise.resolve();
  private readonly s: FfmpegRunnerStats = {
    running: false,
    pid: null,
    starts: 0,
    restarts: 0,
    events: { exit: 0, 'spawn-failed': 0, stall: 0 },
    lastExit: null,
    restartAt: null,
  };

  constructor(private readonly o: FfmpegRunnerOptions) {
    if (!exitHookInstalled) {
      exitHookInstalled = true;
      process.on('exit', killLiveChildren);
    }
  }

  get pid(): number | null {
    return this.child?.pid ?? null;
  }

  stats(): FfmpegRunnerStats {
    return { ...this.s, events: { ...this.s.events }, pid: this.pid, running: this.child !== null };
  }

  start(): void {
    if (!this.stopped) return;
    this.stopped = false;
    this.spawnOnce();
    if (this.o.stallMs > 0)
      this.stallTimer = setInterval(() => this.checkStall(), Math.min(1000, this.o.stallMs));
  }

  /** A frame came out (feeds the stall watchdog and the back-off reset). */
  frame(): void {
    this.lastFrameAt = this.o.now();
    this.sawFrame = true;
  }

  /** Stops ffmpeg for good: SIGTERM, SIGKILL after 2 s; resolves once it has exited. */
  async stop(): Promise<void> {
    this.stopped = true;
    if (this.restartTimer) clearTimeout(this.restartTimer);
    if (this.stallTimer) clearInterval(this.stallTimer);
    this.restartTimer = this.stallTimer = null;
    this.s.restartAt = null;
    const child = this.child;
    if (child) {
      child.kill('SIGTERM');
      const hard = setTimeout(() => child.kill('SIGKILL'), KILL_AFTER_MS);
      await this.exited;
      clearTimeout(hard);
    }
  }

  private spawnOnce(): void {
    this.restartTimer = null;
    this.s.restartAt = null;
    this.stderrTail = '';
    this.sawFrame = false;
    this.startedAt = this.lastFrameAt = this.o.now();
    const fds = Object.keys(this.o.outputs).map(Number);
    const stdio: ('ignore' | 'pipe')[] = ['ignore', 'ignore', 'pipe'];
    for (const fd of fds) stdio[fd] = 'pipe';
    for (let i = 0; i < stdio.length; i++) stdio[i] ??= 'ignore';
    this.o.onStart();
    let child: ChildProcess;
    try {
      child = spawn(this.o.command, this.o.args, { stdio });
    } catch (err) {
      this.ended(null, null, `cannot run ${this.o.command}: ${(err as Error).message}`, true);
      return;
    }
    this.child = child;
    this.s.starts++;
    live.add(child);
    let resolveExited!: () => void;
    this.exited = new Promise((r) => (resolveExited = r));
    for (const fd of fds) {
      const stream = child.stdio[fd] as NodeJS.ReadableStream | null;
      stream?.on('data', (chunk: Buffer) => this.o.outputs[fd]!(chunk));
      stream?.on('error', () => {}); // the exit below says why
    }
    child.stderr?.setEncoding('utf8');
    child.stderr?.on('data', (text: string) => {
      this.stderrTail = (this.stderrTail + text).slice(-STDERR_TAIL);
    });
    let spawnError: Error | null = null;
    child.once('error', (err) => {
      spawnError = err;
      if (child.pid === undefined) {
        live.delete(child);
        this.child = null;
        resolveExited();
        this.ended(null, null, `cannot run ${this.o.command}: ${err.message}`, true);
      }
    });
    child.once('close', (code, signal) => {
      live.delete(child);
      if (this.child !== child) return;
      this.child = null;
      resolveExited();
      const line = lastLine(this.stderrTail);
      const status = signal ? `killed by ${signal}` : `exit status ${code}`;
      const reason = spawnError
        ? `cannot run ${this.o.command}: ${(spawnError as Error).message}`
        : line
          ? `${line} (${status})`
          : status;
      this.ended(code, signal, reason, false);
    });
  }

  private ended(
    code: number | null,
    signal: NodeJS.Signals | null,
    reason: string,
    spawnFailed: boolean,
  ): void {
    const ranMs = this.o.now() - this.startedAt;
    const exit: FfmpegExit = { code, signal, reason, ranMs };
    this.s.lastExit = exit;
    if (this.stopped) {
      this.o.onExit(exit, null);
      return;
    }
    this.s.events[spawnFailed ? 'spawn-failed' : 'exit']++;
    this.o.onEvent(spawnFailed ? 'spawn-failed' : 'exit', reason);
    if (this.sawFrame && ranMs >= this.o.backoff.healthyMs) this.failures = 0;
    const delay = backoffDelay(this.failures++, this.o.backoff);
    this.o.onExit(exit, delay);
    this.s.restartAt = this.o.now() + delay;
    this.restartTimer = setTimeout(() => {
      if (this.stopped) return;
      this.s.restarts++;
      this.spawnOnce();
    }, delay);
  }

  private checkStall(): void {
    const child = this.child;
    if (!child || this.o.now() - this.lastFrameAt < this.o.stallMs) return;
    this.s.events.stall++;
    this.o.onEvent('stall', `no frame for ${this.o.stallMs} ms: restarting ffmpeg`);
    this.lastFrameAt = this.o.now();
    child.kill('SIGKILL');
  }
}

/** The last non-empty line of ffmpeg's stderr, trimmed to 300 characters. */
export function lastLine(text: string): string {
  const lines = text.split(/\r?\n|\r/).map((l) => l.trim());
  for (let i = lines.length - 1; i >= 0; i--) if (lines[i]) return lines[i]!.slice(0, 300);
  return '';
}

/**
 * ffmpeg's version line, or null when `command` cannot be run: for a clear message before any
 * camera starts (`armtwin up --camera testsrc` without ffmpeg says so and goes on without it).
 */
export function ffmpegVersion(command = 'ffmpeg'): string | null {
  const r = spawnSync(command, ['-hide_banner', '-version'], { encoding: 'utf8', timeout: 10_000 });
  return r.status === 0 ? (r.stdout.split('\n')[0]?.trim() ?? '') : null;
}
