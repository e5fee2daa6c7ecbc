/**
 * Integration-test harness for the middleware: runs it as a child process (so it can be
 * SIGKILLed), publishes with `mosquitto_pub`, counts points in InfluxDB. Used by
 * tests/integration/middleware-*.test.ts and the rate benchmark.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const REPO = path.resolve(
  path.dirname(fileURLToPath(import.meta.url)),
  '..',
  '..',
  '..',
  '..',
);
const MAIN = path.join(REPO, 'apps', 'middleware', 'src', 'main.ts');
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

export interface MiddlewareProcess {
  child: ChildProcess;
  port: number;
  logFile: string;
  metrics(): Promise<Record<string, number>>;
  health(): Promise<{ status: number; body: Record<string, unknown> }>;
  kill(): Promise<void>;
  stop(): Promise<number | null>;
}

/**
 * The environment of a middleware on the tests' own services: `broker`, `influx` (omitted:
 * no storage), a fixed client id, and its spool in `dir/<spool>`. `extra` adds or overrides.
 */
export function middlewareEnv(
  services: {
    mqttUrl: string;
    influx?: { url: string; bucket: string; token?: string; org?: string };
  },
  clientId: string,
  dir: string,
  extra: Record<string, string> = {},
  spool = 'spool',
): Record<string, string> {
  return {
    MQTT_URL: services.mqttUrl,
    MQTT_CLIENT_ID: clientId,
    ...(services.influx
      ? {
          INFLUX_URL: services.influx.url,
          INFLUX_BUCKET: services.influx.bucket,
          INFLUX_TOKEN: services.influx.token ?? '',
          INFLUX_ORG: services.influx.org ?? '',
        }
      : {}),
    SPOOL_DIR: path.join(dir, spool),
    ...extra,
  };
}

/** Starts `node --import tsx apps/middleware/src/main.ts` with env; waits for /healthz. */
export async function spawnMiddleware(
  env: Record<string, string>,
  port: number,
  logFile: string,
): Promise<MiddlewareProcess> {
  const fd = fs.openSync(logFile, 'a');
  const child = spawn(process.execPath, ['--import', 'tsx', MAIN], {
    cwd: REPO,
    env: { ...process.env, LOG_LEVEL: 'info', ...env, PORT: String(port), HOST: '127.0.0.1' },
    stdio: ['ignore', fd, fd],
  });
  fs.closeSync(fd);
  const exited = new Promise<number | null>((resolve) =>
    child.once('exit', (code) => resolve(code)),
  );
  let gone = false;
  void exited.then(() => (gone = true));
  const base = `http://127.0.0.1:${port}`;
  const health = async () => {
    const res = await fetch(`${base}/healthz`);
    return { status: res.status, body: (await res.json()) as Record<string, unknown> };
  };
  const deadline = Date.now() + 30_000;
  for (;;) {
    if (gone)
      throw new Error(
        `middleware exited at start:\n${fs.readFileSync(logFile, 'utf8').slice(-2000)}`,
      );
    const h = await health().catch(() => null);
    if (h && (h.body.mqtt as { connected: boolean }).connected) break;
    if (Date.now() > deadline)
      throw new Error(`middleware not ready:\n${fs.readFileSync(logFile, 'utf8').slice(-2000)}`);
    await sleep(100);
  }
  return {
    child,
    port,
    logFile,
    health,
    async metrics() {
      const text = await (await fetch(`${base}/metrics`)).text();
      return parseMetrics(text);
    },
    async kill() {
      child.kill('SIGKILL');
      await exited;
    },
    async stop() {
      child.kill('SIGTERM');
      return exited;
    },
  };
}

/** `name{labels} value` lines → { 'name{labels}': value }. */
export function parseMetrics(text: string): Record<string, number> {
  const out: Record<string, number> = {};
  for (const line of text.split('\n')) {
    if (!line || line.startsWith('#')) continue;
    const i = line.lastIndexOf(' ');
    out[line.slice(0, i).replace('armtwin_middleware_', '')] = Number(line.slice(i + 1));
  }
  return out;
}

/** A `mosquitto_pub -l` process: one MQTT message per line written to it. */
export function startPublisher(
  port: number,
  topic: string,
  qos: 0 | 1,
  clientId = `pub-${process.pid}-${Math.random().toString(36).slice(2, 8)}`,
) {
  const child = spawn(
    'mosquitto_pub',
    ['-h', '127.0.0.1', '-p', String(port), '-q', String(qos), '-t', topic, '-i', clientId, '-l'],
    { stdio: ['pipe', 'ignore', 'inherit'] },
  );
  const exited = new Promise<number | null>((resolve) =>
    child.once('exit', (code) => resolve(code)),
  );
  return {
    /** Writes the messages, `perTick` every `tickMs`, so the stream is spread over time. */
    async send(messages: readonly string[], perTick = messages.length, tickMs = 10): Promise<void> {
      for (let i = 0; i < messages.length; i += perTick) {
        const chunk = messages.slice(i, i + perTick).join('\n') + '\n';
        if (!child.stdin.write(chunk)) await new Promise((r) => child.stdin.once('drain', r));
        if (i + perTick < messages.length) await sleep(tickMs);
      }
    },
    async end(): Promise<number | null> {
      child.stdin.end();
      return exited;
    },
  };
}

/** Publishes messages with one `mosquitto_pub -l` and waits for it to exit. */
export async function publishAll(
  port: number,
  topic: string,
  messages: readonly string[],
  qos: 0 | 1 = 1,
): Promise<void> {
  const p = startPublisher(port, topic, qos);
  await p.send(messages);
  const code = await p.end();
  if (code !== 0) throw new Error(`mosquitto_pub exited with ${code}`);
}

/** `{#000P…!#001P…!…}` state payloads, one $TIM stamp per message (ms t0 + k). */
export function statePayloads(count: number, servos: number, t0: number): string[] {
  const out: string[] = [];
  for (let k = 0; k < count; k++) {
    let group = '';
    for (let id = 0; id < servos; id++) group += `#00${id}P${500 + ((k * 7 + id * 100) % 2001)}!`;
    out.push(`$TIM:${t0 + k}!{${group}}`);
  }
  return out;
}

export interface InfluxTarget {
  url: string;
  /** The database (1.8), or a 2.x bucket's name (2.x maps each bucket to a database). */
  db: string;
  /** A 2.x API token, sent as `Authorization: Token …`. */
  token?: string;
}

/** Runs one InfluxQL SELECT; returns its first series' values (or []). */
export async function select(influx: InfluxTarget, q: string): Promise<unknown[][]> {
  const res = await fetch(`${influx.url}/query?db=${encodeURIComponent(influx.db)}&epoch=u`, {
    method: 'POST',
    headers: influx.token ? { authorization: `Token ${influx.token}` } : {},
    body: new URLSearchParams({ q }),
  });
  const body = (await res.json()) as {
    results?: { series?: { values: unknown[][] }[]; error?: string }[];
  };
  const r = body.results?.[0];
  if (r?.error) throw new Error(r.error);
  return r?.series?.[0]?.values ?? [];
}

/** `SELECT count(field) FROM measurement` (0 when empty). */
export async function countPoints(
  influx: InfluxTarget,
  measurement: string,
  field: string,
): Promise<number> {
  const v = await select(influx, `SELECT count("${field}") FROM "${measurement}"`).catch(() => []);
  return Number(v[0]?.[1] ?? 0);
}

/** Polls until `fn` returns `want` or `timeoutMs` passes; returns the last value. */
export async function waitForValue<T>(
  fn: () => Promise<T>,
  want: T,
  timeoutMs: number,
  everyMs = 250,
): Promise<T> {
  const deadline = Date.now() + timeoutMs;
  let v = await fn();
  while (v !== want && Date.now() < deadline) {
    await sleep(everyMs);
    v = await fn();
  }
  return v;
}

export function tempDir(name: string): string {
  return fs.mkdtempSync(path.join(os.tmpdir(), `armtwin-${name}-`));
}
