/**
 * The simulated arm as a child process (`armtwin sim`, the real CLI), plus an mqtt.js observer
 * that records what appears on the arm's topics, for end-to-end tests.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { armTopics, createReader, type Frame } from '@armtwin/protocol';
import { REPO_ROOT } from '../../helpers/services.ts';

const CLI = path.join(REPO_ROOT, 'apps/cli/bin/armtwin.mjs');

export interface SimProcess {
  armId: string;
  logFile: string;
  child: ChildProcess;
  /** SIGKILL: a crash (the broker then publishes the retained will `0`). */
  kill(): Promise<void>;
  /** SIGTERM and wait. */
  stop(): Promise<void>;
}

/** Starts `armtwin sim --mqtt <url> --arm <id>` with its output in `logFile`. */
export function startSim(
  mqttUrl: string,
  armId: string,
  logFile: string,
  extraArgs: string[] = [],
): SimProcess {
  fs.mkdirSync(path.dirname(logFile), { recursive: true });
  const out = fs.openSync(logFile, 'a');
  const child = spawn(
    process.execPath,
    [CLI, 'sim', '--mqtt', mqttUrl, '--arm', armId, ...extraArgs],
    {
      cwd: REPO_ROOT,
      stdio: ['ignore', out, out],
      env: { ...process.env, LOG_LEVEL: process.env.LOG_LEVEL ?? 'info' },
    },
  );
  fs.closeSync(out);
  const exited = new Promise<void>((resolve) => child.once('exit', () => resolve()));
  const end = async (signal: NodeJS.Signals) => {
    if (child.exitCode === null && child.signalCode === null) child.kill(signal);
    await exited;
  };
  return { armId, logFile, child, kill: () => end('SIGKILL'), stop: () => end('SIGTERM') };
}

export interface Received {
  at: number;
  topic: string;
  text: string;
  qos: number;
}

/** An mqtt.js client watching `arm/{id}/{control,status,online}`. */
export class ArmObserver {
  readonly messages: Received[] = [];
  /** Latest pulse per servo from the status topic. */
  readonly pwm: number[] = [];
  /** Latest angle per servo (§8 angle frames: a bus arm's, an angle servo's), degrees. */
  readonly angles: number[] = [];
  readonly health: { temp: number; mv: number }[] = [];
  readonly kmsReplies: number[] = [];
  online: string | null = null;
  private readonly reader = createReader({
    onFrame: (f) => this.take(f),
    onGroup: (g) => g.frames.forEach((f) => this.take(f)),
  });

  private constructor(
    readonly client: MqttClient,
    readonly armId: string,
  ) {}

  /** `qos` of its subscriptions (0 on a NATS cluster: no JetStream consumer to lose to a kill). */
  static async connect(mqttUrl: string, armId: string, qos: 0 | 1 = 1): Promise<ArmObserver> {
    const client = await mqtt.connectAsync(mqttUrl, {
      clientId: `e2e-observer-${armId}-${process.pid}`,
    });
    const o = new ArmObserver(client, armId);
    const t = armTopics(armId);
    client.on('message', (topic, payload, packet) => {
      const text = payload.toString('latin1');
      o.messages.push({ at: Date.now(), topic, text, qos: packet.qos });
      if (topic === t.status) o.reader.feed(text);
      if (topic === t.online) o.online = text;
    });
    await client.subscribeAsync([t.control, t.status, t.online], { qos });
    return o;
  }

  private take(f: Frame): void {
    if (f.type === 'position') this.pwm[f.id] = f.pwm;
    else if (f.type === 'angle') this.angles[f.id] = f.deg;
    else if (f.type === 'health') this.health[f.id] = { temp: f.temp, mv: f.mv };
    else if (f.type === 'kmsResult') this.kmsReplies.push(f.code);
  }

  /** Messages on the control topic since `since` (ms epoch). */
  controlMessages(since = 0): Received[] {
    const topic = armTopics(this.armId).control;
    return this.messages.filter((m) => m.topic === topic && m.at >= since);
  }

  /** Payloads on the control topic since `since` (ms epoch). */
  control(since = 0): string[] {
    return this.controlMessages(since).map((m) => m.text);
  }

  /** Control payloads since `since`, without the HUD's `$PNG` round-trip pings. */
  commands(since = 0): string[] {
    return this.control(since).filter((t) => !/^\$PNG:\d+!$/.test(t));
  }

  /** Publishes a runtime fault for the simulator (`arm/{id}/sim`). */
  async fault(json: object): Promise<void> {
    await this.client.publishAsync(`arm/${this.armId}/sim`, JSON.stringify(json), { qos: 1 });
  }

  async close(): Promise<void> {
    await this.client.endAsync(true);
  }
}

/** Polls `fn` until it returns a truthy value or `timeoutMs` passes. */
export async function until<T>(
  fn: () => T,
  timeoutMs: number,
  what: string,
): Promise<NonNullable<T>> {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = fn();
    if (v) return v as NonNullable<T>;
    if (Date.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 50));
  }
}
