/**
 * Shared by the sim, gateway and start integration tests: run an `armtwin` command as a child
 * process, and watch an arm's status topic through a real broker, decoded with the protocol
 * reader, waiting for what a test expects.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import path from 'node:path';
import mqtt, { type IClientOptions, type MqttClient } from 'mqtt';
import { createReader, type Frame, type Group } from '@armtwin/protocol';
import { REPO_ROOT } from '../helpers/services.ts';

export const ARMTWIN = path.join(REPO_ROOT, 'apps', 'cli', 'bin', 'armtwin.mjs');

export interface Child {
  proc: ChildProcess;
  output(): string;
  /** SIGTERM (or `signal`); resolves with the exit code. */
  stop(signal?: NodeJS.Signals): Promise<number | null>;
}

const children = new Set<ChildProcess>();
process.on('exit', () => {
  for (const c of children) c.kill('SIGKILL');
});

/** With `stdin`, the child's stdin is a pipe (`proc.stdin`), else it reads nothing. */
export function runNode(
  args: string[],
  env: Record<string, string> = {},
  { stdin = false }: { stdin?: boolean } = {},
): Child {
  const proc = spawn(process.execPath, args, {
    cwd: REPO_ROOT,
    env: { ...process.env, ...env },
    stdio: [stdin ? 'pipe' : 'ignore', 'pipe', 'pipe'],
  });
  children.add(proc);
  let out = '';
  proc.stdout!.on('data', (d: Buffer) => (out += d.toString()));
  proc.stderr!.on('data', (d: Buffer) => (out += d.toString()));
  const exited = new Promise<number | null>((resolve) =>
    proc.once('exit', (code) => {
      children.delete(proc);
      resolve(code);
    }),
  );
  return {
    proc,
    output: () => out,
    async stop(signal = 'SIGTERM') {
      if (proc.exitCode === null && proc.signalCode === null) proc.kill(signal);
      const timer = setTimeout(() => proc.kill('SIGKILL'), 10_000);
      const code = await exited;
      clearTimeout(timer);
      return code;
    },
  };
}

export const armtwin = (args: string[], env?: Record<string, string>, opts?: { stdin?: boolean }) =>
  runNode([ARMTWIN, ...args], env, opts);

/** A decoded status item: a top-level frame or a group, with the `$TIM` it came under. */
/**
 * `armtwin up` (through `script`, e.g. scripts/start.mjs or the CLI) on free HTTP and MQTT ports,
 * resolved once it prints that it is running; fails with its output if it exits or takes 30 s.
 * Without the second arm (`--no-so101`: its emulated bus polls all the time, load no test here
 * needs; tests/integration/up-so101.test.ts runs `npm start` with it).
 */
export async function startUpProcess(
  script: string[],
  args: string[],
  ports: { httpPort: number; mqttPort: number },
  env: Record<string, string> = {},
): Promise<Child> {
  const up = runNode(
    [
      ...script,
      '--no-so101',
      ...args,
      ...['--port', String(ports.httpPort), '--mqtt-port', String(ports.mqttPort)],
    ],
    env,
  );
  const deadline = Date.now() + 30_000;
  while (!up.output().includes('armtwin is running')) {
    if (Date.now() > deadline || up.proc.exitCode !== null)
      throw new Error(`armtwin up did not start:\n${up.output()}`);
    await new Promise((r) => setTimeout(r, 100));
  }
  return up;
}

export type StatusItem = { frame: Frame; time?: number } | { group: Group; time?: number };

export class StatusWatcher {
  readonly items: StatusItem[] = [];
  readonly retained = new Map<string, string>();
  /** Every message on the non-status topics, in order: a brief 0 between two 1s is kept. */
  readonly history: { topic: string; payload: string }[] = [];
  private waiters: (() => void)[] = [];

  private constructor(
    readonly client: MqttClient,
    readonly armId: string,
  ) {}

  static async connect(
    url: string,
    armId: string,
    options: IClientOptions = {},
  ): Promise<StatusWatcher> {
    const client = await mqtt.connectAsync(url, {
      reconnectPeriod: 500,
      connectTimeout: 5000,
      ...options,
    });
    const w = new StatusWatcher(client, armId);
    const reader = createReader({
      onFrame: (frame) => frame.type !== 'time' && w.push({ frame, time: frame.time }),
      onGroup: (group) => w.push({ group, time: group.time }),
    });
    client.on('message', (topic, payload) => {
      if (topic === `arm/${armId}/status`) {
        reader.clearStamp();
        reader.feed(payload);
      } else {
        w.retained.set(topic, payload.toString());
        w.history.push({ topic, payload: payload.toString() });
        w.notify();
      }
    });
    await client.subscribeAsync(
      [`arm/${armId}/status`, `arm/${armId}/online`, `arm/${armId}/sim/faults`],
      { qos: 1 },
    );
    return w;
  }

  private push(item: StatusItem) {
    this.items.push(item);
    this.notify();
  }

  private notify() {
    for (const w of this.waiters.splice(0)) w();
  }

  /** Publishes on the arm's control topic. */
  send(payload: string): Promise<unknown> {
    return this.client.publishAsync(`arm/${this.armId}/control`, payload, { qos: 1 });
  }

  /** Waits until `test` returns a value (not undefined) or `timeoutMs` passes. */
  async until<T>(test: () => T | undefined, timeoutMs = 10_000, what = 'condition'): Promise<T> {
    const deadline = Date.now() + timeoutMs;
    for (;;) {
      const value = test();
      if (value !== undefined) return value;
      const left = deadline - Date.now();
      if (left <= 0) throw new Error(`timed out waiting for ${what}`);
      await new Promise<void>((resolve) => {
        const t = setTimeout(resolve, Math.min(left, 200));
        this.waiters.push(() => (clearTimeout(t), resolve()));
      });
    }
  }

  /** The first top-level frame after index `from` matching `test`, with its `$TIM`. */
  frame(test: (f: Frame) => boolean, from = 0, timeoutMs?: number) {
    return this.until(
      () => {
        for (let i = from; i < this.items.length; i++) {
          const it = this.items[i]!;
          if ('frame' in it && test(it.frame)) return { frame: it.frame, time: it.time ?? NaN };
        }
        return undefined;
      },
      timeoutMs,
      'a status frame',
    );
  }

  /** State samples (position groups of every servo) after index `from`: [time, pwm of servo id]. */
  positions(id: number, from = 0): [number, number][] {
    const out: [number, number][] = [];
    for (let i = from; i < this.items.length; i++) {
      const it = this.items[i]!;
      if (!('group' in it) || it.group.frames.length < 6) continue;
      const f = it.group.frames.find((x) => x.type === 'position' && x.id === id);
      if (f?.type === 'position') out.push([it.time ?? NaN, f.pwm]);
    }
    return out;
  }

  /** State groups of `servos` angle frames (§8) after index `from`: the angle of servo `id` in each. */
  angles(id: number, from = 0, servos = 6): number[] {
    const out: number[] = [];
    for (const it of this.items.slice(from)) {
      if (!('group' in it) || it.group.frames.length !== servos) continue;
      const f = it.group.frames.find((x) => x.type === 'angle' && x.id === id);
      if (f?.type === 'angle') out.push(f.deg);
    }
    return out;
  }

  /** Resolves once the arm's retained `online` is `1`. */
  online(timeoutMs = 20_000): Promise<true> {
    return this.until(
      () => (this.retained.get(`arm/${this.armId}/online`) === '1' ? true : undefined),
      timeoutMs,
      'online 1',
    );
  }

  /** Angle samples (state groups, §8 angle frames) of servo `id` after index `from`: [time, deg]. */
  angleSamples(id: number, from = 0): [number, number][] {
    const out: [number, number][] = [];
    for (let i = from; i < this.items.length; i++) {
      const it = this.items[i]!;
      if (!('group' in it)) continue;
      const f = it.group.frames.find((x) => x.type === 'angle' && x.id === id);
      if (f?.type === 'angle') out.push([it.time ?? NaN, f.deg]);
    }
    return out;
  }

  /** Latest health of servo `id`. */
  health(id: number): { temp: number; mv: number } | undefined {
    for (let i = this.items.length - 1; i >= 0; i--) {
      const it = this.items[i]!;
      if (!('group' in it)) continue;
      const f = it.group.frames.find((x) => x.type === 'health' && x.id === id);
      if (f?.type === 'health') return { temp: f.temp, mv: f.mv };
    }
    return undefined;
  }

  close(): Promise<void> {
    return this.client.endAsync(true);
  }
}
