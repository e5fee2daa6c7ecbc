/**
 * Spawning a throwaway service process, waiting for its ports, capturing its log, and making
 * sure it never outlives the test process.
 *
 * - stdout and stderr go straight to `<dir>/<name>.log` (a file descriptor handed to the child,
 *   so the log is complete even if Node dies first).
 * - Every live child is in `live`; on `exit`, SIGINT, SIGTERM and SIGHUP of the test process
 *   each one gets SIGKILL. Where util-linux `setpriv` exists the child is also started with
 *   `--pdeathsig KILL`, so the kernel kills it if the test process is itself SIGKILLed.
 * - `dispose({ keepLogs })` copies the temp dir's logs and configs to
 *   `test-results/services/<name>-<timestamp>/` when asked, then removes the temp dir.
 *   A service never disposed has its temp dir removed when the test process exits; dirs of
 *   SIGKILLed test processes are swept by the next one (each dir holds its owner's pid).
 * - `startService` retries with fresh ports when the service reports "address already in use"
 *   (a free port can be taken between asking the OS and binding it); when a start fails for
 *   any other reason the logs are kept and the error names where.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { keepLogs, makeTempDir, removeDir, removeTrackedDirs, tail, trackDir } from './files.ts';
import { canConnect, freePorts } from './ports.ts';

const SETPRIV = '/usr/bin/setpriv';
const hasSetpriv = fs.existsSync(SETPRIV);
const live = new Set<ChildProcess>();
let handlersInstalled = false;

function killAllAndClean(): void {
  for (const child of live) {
    try {
      child.kill('SIGKILL');
    } catch {
      // already gone
    }
  }
  live.clear();
  removeTrackedDirs();
}

function installExitHandlers(): void {
  if (handlersInstalled) return;
  handlersInstalled = true;
  process.on('exit', killAllAndClean);
  for (const signal of ['SIGINT', 'SIGTERM', 'SIGHUP'] as const) {
    const onSignal = () => {
      killAllAndClean();
      process.removeListener(signal, onSignal);
      // Nobody else handles it: behave as if we had not been listening.
      if (process.listenerCount(signal) === 0) process.kill(process.pid, signal);
    };
    process.on(signal, onSignal);
  }
}

export interface ServiceSpec {
  /** Short name: temp dir prefix, log file name, kept-logs folder prefix. */
  name: string;
  command: string;
  args: string[];
  /** The service's temp dir (its working directory). */
  dir: string;
  host: string;
  /** Every port that must accept connections before the service counts as up. */
  ports: number[];
  /** Milliseconds to wait for the ports and `ready`. */
  startTimeoutMs: number;
  /** An extra readiness check after the ports accept connections (e.g. HTTP /ping); retried. */
  ready?: () => Promise<boolean>;
}

const sleep = (ms: number) => new Promise((resolve) => setTimeout(resolve, ms));

/** One service process that can be stopped, killed and started again in the same dir. */
/** What a test may do with a service it started: the lifecycle every service helper offers. */
export interface ServiceLifecycle {
  /** The temp dir: config, data, log. */
  dir: string;
  confFile: string;
  logFile: string;
  readonly running: boolean;
  /** Starts the service again (same dir, same ports) after stop() or kill(). */
  start(): Promise<void>;
  /** Clean shutdown (SIGTERM). The temp dir stays. */
  stop(): Promise<void>;
  /** stop() then start(). */
  restart(): Promise<void>;
  /** SIGKILL: a crash. The temp dir stays. */
  kill(): Promise<void>;
  /** Final teardown: kill if running, keep logs if asked (returns where), remove the temp dir. */
  dispose(opts?: { keepLogs?: boolean }): Promise<string | undefined>;
}

export class ServiceProcess {
  readonly logFile: string;
  private child: ChildProcess | undefined;
  private exited: Promise<void> = Promise.resolve();
  private disposed = false;

  constructor(readonly spec: ServiceSpec) {
    this.logFile = path.join(spec.dir, `${spec.name}.log`);
    trackDir(spec.dir);
  }

  get running(): boolean {
    return this.child !== undefined;
  }

  get pid(): number | undefined {
    return this.child?.pid;
  }

  /** Spawns the process and waits until it is ready; throws (with the log's tail) if it is not. */
  async start(): Promise<void> {
    if (this.disposed) throw new Error(`${this.spec.name}: already disposed`);
    if (this.child) return;
    installExitHandlers();
    const { command, args, dir } = this.spec;
    const fd = fs.openSync(this.logFile, 'a');
    const [file, argv] = hasSetpriv
      ? [SETPRIV, ['--pdeathsig', 'KILL', '--', command, ...args]]
      : [command, args];
    const child = spawn(file, argv, { cwd: dir, stdio: ['ignore', fd, fd] });
    fs.closeSync(fd);
    this.child = child;
    live.add(child);
    let exitInfo = '';
    this.exited = new Promise((resolve) => {
      child.once('exit', (code, signal) => {
        exitInfo = `exited with ${signal ?? `code ${code}`}`;
        live.delete(child);
        if (this.child === child) this.child = undefined;
        resolve();
      });
      child.once('error', (err) => {
        exitInfo = `failed to spawn: ${err.message}`;
        live.delete(child);
        if (this.child === child) this.child = undefined;
        resolve();
      });
    });
    const deadline = Date.now() + this.spec.startTimeoutMs;
    while (true) {
      if (this.child !== child) {
        throw new Error(
          `${this.spec.name} ${exitInfo} before it was ready; log:\n${tail(this.logFile)}`,
        );
      }
      if (await this.isReady()) return;
      if (Date.now() > deadline) {
        await this.kill();
        throw new Error(
          `${this.spec.name} not ready after ${this.spec.startTimeoutMs} ms; log:\n${tail(this.logFile)}`,
        );
      }
      await sleep(50);
    }
  }

  private async isReady(): Promise<boolean> {
    for (const port of this.spec.ports) {
      if (!(await canConnect(this.spec.host, port))) return false;
    }
    return this.spec.ready ? this.spec.ready().catch(() => false) : true;
  }

  /** SIGTERM (a clean shutdown: Mosquitto saves its persistence file), SIGKILL after graceMs. */
  async stop(graceMs = 10_000): Promise<void> {
    const child = this.child;
    if (!child) return;
    child.kill('SIGTERM');
    const timer = setTimeout(() => child.kill('SIGKILL'), graceMs);
    await this.exited;
    clearTimeout(timer);
  }

  /** SIGKILL: a crash, nothing saved. */
  async kill(): Promise<void> {
    const child = this.child;
    if (!child) return;
    child.kill('SIGKILL');
    await this.exited;
  }

  /**
   * Final teardown: kills the process if it still runs, keeps the logs if asked (returns
   * where), removes the temp dir. Safe to call twice.
   */
  async dispose(opts: { keepLogs?: boolean } = {}): Promise<string | undefined> {
    if (this.disposed) return undefined;
    await this.stop(2_000);
    this.disposed = true;
    const kept = opts.keepLogs ? keepLogs(this.spec.dir, this.spec.name) : undefined;
    removeDir(this.spec.dir);
    return kept;
  }
}

/**
 * Makes a temp dir and `portCount` free ports, lets `build` write the config and describe
 * the process, starts it. Retries (new dir, new ports) up to 3 times on a port conflict.
 */
export async function startService(
  name: string,
  portCount: number,
  build: (dir: string, ports: number[]) => ServiceSpec,
): Promise<ServiceProcess> {
  for (let attempt = 1; ; attempt++) {
    const dir = makeTempDir(name);
    let service: ServiceProcess;
    try {
      service = new ServiceProcess(build(dir, await freePorts(portCount)));
    } catch (err) {
      removeDir(dir);
      throw err;
    }
    try {
      await service.start();
      return service;
    } catch (err) {
      const portTaken = /address already in use/i.test(tail(service.logFile, 200));
      if (portTaken && attempt < 3) {
        await service.dispose();
        continue;
      }
      const kept = await service.dispose({ keepLogs: true });
      throw new Error(`${(err as Error).message}\n(logs kept in ${kept})`, { cause: err });
    }
  }
}
