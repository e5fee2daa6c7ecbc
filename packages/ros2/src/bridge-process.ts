/**
 * The rclpy bridge process (python/armtwin_ros2/bridge.py) as a TypeScript object: started from
 * the ROS 2 venv, spoken to in JSON lines (./wire.ts). Subscriptions call back with plain
 * objects; publications are fire-and-forget, or acknowledged when a caller waits for a
 * subscriber. What the bridge reports as wrong, and stdout lines that are not events, are counted
 * by kind and handed to `onError`; nothing is thrown from a callback.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import readline from 'node:readline';
import { ros2Env, ros2Python } from './venv.ts';
import {
  parseEvent,
  ROS2_ERROR_KINDS,
  type Ros2Command,
  type Ros2Messages,
  type Ros2MessageType,
} from './wire.ts';

export type Ros2BridgeErrorKind = (typeof ROS2_ERROR_KINDS)[number] | 'bad-event';

export interface Ros2BridgeOptions {
  /** ROS_DOMAIN_ID, 0–232; undefined: the environment's (ROS_DOMAIN_ID), else 0. */
  domain: number | undefined;
  /** The ROS 2 node's name (default `armtwin_bridge_<pid>`). */
  nodeName: string | undefined;
  /** Longest wait for the process to say it is ready, ms (rclpy's start takes ~1 s). */
  startTimeoutMs: number;
  /** Told of each error the bridge reports and each line that is not an event. */
  onError: (kind: Ros2BridgeErrorKind, message: string) => void;
  /** The environment the venv and the process are found with. */
  env: NodeJS.ProcessEnv;
}

export const DEFAULT_ROS2_BRIDGE_OPTIONS: Ros2BridgeOptions = {
  domain: undefined,
  nodeName: undefined,
  startTimeoutMs: 30_000,
  onError: () => {},
  env: process.env,
};

/** Largest ROS_DOMAIN_ID FastDDS accepts on Linux. */
export const MAX_ROS2_DOMAIN = 232;

type Handler = (msg: never) => void;
interface Pending {
  resolve: (subscribers: number) => void;
  reject: (err: Error) => void;
}

export class Ros2Bridge {
  readonly errors: Record<Ros2BridgeErrorKind, number> = {
    'bad-json': 0,
    'bad-command': 0,
    'bad-message': 0,
    ros: 0,
    'bad-event': 0,
  };
  /** The ROS_DOMAIN_ID the node is on, as the process reports it. */
  domain = NaN;
  /** Resolves with the exit code when the process ends, for whatever reason. */
  readonly exited: Promise<number | null>;
  private readonly handlers = new Map<string, Handler[]>();
  private readonly pending = new Map<number, Pending>();
  private nextId = 1;
  private stderr = '';
  private ready: (() => void) | undefined;

  private constructor(
    private readonly proc: ChildProcess,
    private readonly options: Ros2BridgeOptions,
  ) {
    this.exited = new Promise((resolve) =>
      proc.once('exit', (code) => {
        for (const p of this.pending.values())
          p.reject(new Error(`the ROS 2 bridge exited (${code}): ${this.stderrTail()}`));
        this.pending.clear();
        resolve(code);
      }),
    );
    proc.stderr!.on(
      'data',
      (d: Buffer) => (this.stderr = (this.stderr + d.toString()).slice(-4000)),
    );
    readline.createInterface({ input: proc.stdout! }).on('line', (line) => this.onLine(line));
  }

  /** Starts the process and resolves once its node is up; throws with its stderr if it is not. */
  static async start(options: Partial<Ros2BridgeOptions> = {}): Promise<Ros2Bridge> {
    const o = { ...DEFAULT_ROS2_BRIDGE_OPTIONS, ...options };
    if (
      o.domain !== undefined &&
      !(Number.isInteger(o.domain) && o.domain >= 0 && o.domain <= MAX_ROS2_DOMAIN)
    )
      throw new RangeError(`ROS 2 domain must be an integer in 0–${MAX_ROS2_DOMAIN}`);
    const args = ['-m', 'armtwin_ros2.bridge'];
    if (o.domain !== undefined) args.push('--domain', String(o.domain));
    if (o.nodeName) args.push('--name', o.nodeName);
    const proc = spawn(ros2Python(o.env), args, {
      env: ros2Env(o.env),
      stdio: ['pipe', 'pipe', 'pipe'],
    });
    const bridge = new Ros2Bridge(proc, o);
    let timer: NodeJS.Timeout | undefined;
    try {
      await Promise.race([
        new Promise<void>((resolve) => (bridge.ready = () => resolve())),
        bridge.exited.then((code) => {
          throw new Error(
            `the ROS 2 bridge exited (${code}) before it was ready: ${bridge.stderrTail()}`,
          );
        }),
        new Promise<never>((_, reject) => {
          timer = setTimeout(
            () =>
              reject(
                new Error(
                  `the ROS 2 bridge was not ready in ${o.startTimeoutMs} ms: ${bridge.stderrTail()}`,
                ),
              ),
            o.startTimeoutMs,
          );
        }),
      ]);
    } catch (err) {
      proc.kill('SIGKILL');
      throw err;
    } finally {
      clearTimeout(timer);
    }
    return bridge;
  }

  /** The process id (for a CPU meter). */
  get pid(): number {
    return this.proc.pid ?? -1;
  }

  /** Subscribes `topic`; resolves once the subscription exists. `durable`: a latched topic. */
  async subscribe<T extends Ros2MessageType>(
    topic: string,
    type: T,
    onMessage: (msg: Ros2Messages[T]) => void,
    opts: { durable?: boolean } = {},
  ): Promise<void> {
    const key = `${type} ${topic}`;
    this.handlers.set(key, [...(this.handlers.get(key) ?? []), onMessage as Handler]);
    await this.request({ op: 'subscribe', topic, type, ...opts });
  }

  /** Publishes without waiting (a bad message is reported through `onError`). */
  publish<T extends Ros2MessageType>(
    topic: string,
    type: T,
    msg: Ros2Messages[T],
    opts: { durable?: boolean } = {},
  ): void {
    this.send({ op: 'publish', topic, type, msg, ...opts });
  }

  /**
   * Makes the publisher (waiting up to `waitMs` for a subscriber to be matched) and resolves with
   * the number of subscribers: a message published after it reaches those.
   */
  advertise(
    topic: string,
    type: Ros2MessageType,
    opts: { durable?: boolean; waitMs?: number } = {},
  ): Promise<number> {
    return this.request({
      op: 'advertise',
      topic,
      type,
      durable: opts.durable,
      wait_ms: opts.waitMs ?? 0,
    });
  }

  /** Closes stdin (the process shuts rclpy down and exits); kills it if it has not in 5 s. */
  async close(): Promise<number | null> {
    this.proc.stdin!.end();
    const timer = setTimeout(() => this.proc.kill('SIGKILL'), 5000);
    const code = await this.exited;
    clearTimeout(timer);
    return code;
  }

  private request(cmd: Ros2Command): Promise<number> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.send({ ...cmd, id });
    });
  }

  private send(cmd: Ros2Command): void {
    if (this.proc.stdin!.writable) this.proc.stdin!.write(`${JSON.stringify(cmd)}\n`);
  }

  private stderrTail(): string {
    return this.stderr.trim().split('\n').slice(-5).join(' | ') || '(nothing on stderr)';
  }

  private onLine(line: string): void {
    const parsed = parseEvent(line);
    if (!parsed.ok) return this.fail('bad-event', parsed.error);
    const e = parsed.event;
    switch (e.ev) {
      case 'ready':
        this.domain = e.domain;
        return this.ready?.();
      case 'ack': {
        const p = this.pending.get(e.id);
        this.pending.delete(e.id);
        return p?.resolve(e.subscribers ?? 0);
      }
      case 'message':
        for (const h of this.handlers.get(`${e.type} ${e.topic}`) ?? []) h(e.msg as never);
        return;
      case 'error': {
        const p = e.id == null ? undefined : this.pending.get(e.id);
        if (p && e.id != null) {
          this.pending.delete(e.id);
          p.reject(new Error(`ROS 2 bridge: ${e.kind}: ${e.message}`));
        }
        return this.fail(e.kind, e.message);
      }
      default: {
        const never: never = e;
        return never;
      }
    }
  }

  private fail(kind: Ros2BridgeErrorKind, message: string): void {
    this.errors[kind]++;
    this.options.onError(kind, message);
  }
}
