/**
 * The parts of armtwin a benchmark runs as real processes: the simulator (`armtwin sim`), the
 * middleware (`apps/middleware/src/main.ts`), and bench-only helpers (the bare echo client and
 * the status publisher in ../agents). Each is a tracked child (./proc.ts), on 127.0.0.1 only.
 */
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import mqtt, { type MqttClient } from 'mqtt';
import { freePort } from '../../tests/helpers/ports.ts';
import { spawnChild, sleep, until, type Child } from './proc.ts';
import { parseMetrics } from '../../apps/middleware/test/support/harness.ts';

export const REPO = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const ARMTWIN = path.join(REPO, 'apps', 'cli', 'bin', 'armtwin.mjs');
/**
 * The middleware's entry; `BENCH_MIDDLEWARE_MAIN` names another (a copy of an older
 * `apps/middleware/src` inside this checkout, e.g. under `.scratch/`, so that it finds the same
 * node_modules), for a before/after in one run.
 */
const MIDDLEWARE =
  process.env['BENCH_MIDDLEWARE_MAIN'] || path.join(REPO, 'apps', 'middleware', 'src', 'main.ts');
export const AGENTS = path.join(REPO, 'bench', 'agents');
/** The bench's Mosquitto settings (no Nagle, a deep queue for a subscriber behind). */
export const BROKER_EXTRA = ['set_tcp_nodelay true', 'max_queued_messages 1000000'];

/** Connects an mqtt.js client (clean session, no reconnect storms) and waits for CONNACK. */
export async function connectMqtt(url: string, clientId: string): Promise<MqttClient> {
  return mqtt.connectAsync(url, { clientId, clean: true, reconnectPeriod: 1000, keepalive: 60 });
}

/** Waits until retained `arm/{id}/online` is `1`. */
export async function waitOnline(url: string, armId: string, timeoutMs = 30_000): Promise<void> {
  const c = await connectMqtt(url, `bench-wait-${armId}-${process.pid}`);
  let online = false;
  c.on('message', (_t, p) => (online = p.toString() === '1'));
  await c.subscribeAsync(`arm/${armId}/online`, { qos: 1 });
  const ok = await until(() => online, timeoutMs);
  await c.endAsync();
  if (!ok) throw new Error(`sim ${armId} not online after ${timeoutMs} ms`);
}

/** `armtwin sim --mqtt url --arm id --rate hz` as a child; resolves once it is online. */
export async function startSim(
  url: string,
  armId: string,
  rate: number,
  logFile: string,
): Promise<Child> {
  const child = spawnChild(
    process.execPath,
    [ARMTWIN, 'sim', '--mqtt', url, '--arm', armId, '--rate', String(rate)],
    { cwd: REPO, logFile, env: { ...process.env, LOG_LEVEL: 'warn' } },
  );
  await waitOnline(url, armId);
  return child;
}

/** `armtwin broker` (the embedded Aedes broker) on a free port; resolves once it takes a client. */
export async function startEmbeddedBroker(
  logFile: string,
): Promise<{ child: Child; port: number; url: string }> {
  const port = await freePort();
  const child = spawnChild(process.execPath, [ARMTWIN, 'broker', '--port', String(port)], {
    cwd: REPO,
    logFile,
    env: { ...process.env, LOG_LEVEL: 'warn' },
  });
  const url = `mqtt://127.0.0.1:${port}`;
  const up = await until(
    async () => {
      const c = await mqtt.connectAsync(url, { reconnectPeriod: 0 }).catch(() => null);
      await c?.endAsync();
      return c !== null;
    },
    30_000,
    250,
  );
  if (!up) {
    await child.stop();
    throw new Error('armtwin broker did not start');
  }
  return { child, port, url };
}

/** Runs a bench agent script (`bench/agents/<name>.ts`) through tsx, stdout piped. */
export function startAgent(name: string, args: string[], logFile: string): Child {
  return spawnChild(
    process.execPath,
    ['--import', 'tsx', path.join(AGENTS, `${name}.ts`), ...args],
    {
      cwd: REPO,
      logFile,
      stdout: 'pipe',
    },
  );
}

/** Reads the first JSON line an agent prints on stdout (its result), bounded in time. */
export function agentResult<T>(child: Child, timeoutMs: number): Promise<T> {
  return new Promise((resolve, reject) => {
    let buf = '';
    const timer = setTimeout(
      () => reject(new Error(`agent gave no result in ${timeoutMs} ms`)),
      timeoutMs,
    );
    child.proc.stdout?.on('data', (d: Buffer) => {
      buf += d.toString();
      const nl = buf.indexOf('\n');
      if (nl < 0) return;
      clearTimeout(timer);
      try {
        resolve(JSON.parse(buf.slice(0, nl)) as T);
      } catch (err) {
        reject(err as Error);
      }
    });
    void child.exited.then(() => {
      clearTimeout(timer);
      if (!buf.includes('\n')) reject(new Error('agent exited without a result'));
    });
  });
}

export interface Middleware {
  child: Child;
  port: number;
  metrics(): Promise<Record<string, number>>;
}

/** The middleware as a child (`node --import tsx main.ts`), ready once MQTT is connected. */
export async function startMiddleware(
  env: Record<string, string>,
  logFile: string,
  /** Extra node options before the script (e.g. `--cpu-prof`). */
  nodeArgs: readonly string[] = [],
): Promise<Middleware> {
  const port = await freePort();
  const child = spawnChild(process.execPath, [...nodeArgs, '--import', 'tsx', MIDDLEWARE], {
    cwd: REPO,
    logFile,
    env: { ...process.env, LOG_LEVEL: 'warn', ...env, PORT: String(port), HOST: '127.0.0.1' },
  });
  const base = `http://127.0.0.1:${port}`;
  let exited = false;
  void child.exited.then(() => (exited = true));
  const ready = await until(
    async () => {
      if (exited) return true;
      const res = await fetch(`${base}/healthz`).catch(() => null);
      if (!res) return false;
      const body = (await res.json().catch(() => ({}))) as { mqtt?: { connected?: boolean } };
      return body.mqtt?.connected === true;
    },
    40_000,
    100,
  );
  if (exited || !ready) {
    await child.stop();
    throw new Error(`middleware did not start (log: ${logFile})`);
  }
  return {
    child,
    port,
    async metrics() {
      const text = await (await fetch(`${base}/metrics`)).text();
      return parseMetrics(text);
    },
  };
}

/** The first row of an InfluxQL query's first series in `db` ([] when empty or failed). */
export async function firstRow(influxUrl: string, db: string, q: string): Promise<unknown[]> {
  const res = await fetch(`${influxUrl}/query?db=${encodeURIComponent(db)}`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  }).catch(() => null);
  if (!res?.ok) return [];
  const body = (await res.json()) as { results?: { series?: { values: unknown[][] }[] }[] };
  return body.results?.[0]?.series?.[0]?.values?.[0] ?? [];
}

/** `SELECT count(field) FROM measurement WHERE arm = …` in `db` (0 when empty). */
export async function countPoints(
  influxUrl: string,
  db: string,
  measurement: string,
  field: string,
  arm?: string,
): Promise<number> {
  const where = arm ? ` WHERE "arm" = '${arm}'` : '';
  const row = await firstRow(
    influxUrl,
    db,
    `SELECT count("${field}") FROM "${measurement}"${where}`,
  );
  return Number(row[1] ?? 0);
}

/** Polls a count until it reaches `want` or stops growing for `stallMs` / `timeoutMs` passes. */
export async function waitForCount(
  count: () => Promise<number>,
  want: number,
  timeoutMs: number,
  stallMs = 8000,
): Promise<{ got: number; ms: number }> {
  const t0 = Date.now();
  let got = await count();
  let last = got;
  let lastChange = Date.now();
  while (got < want && Date.now() - t0 < timeoutMs && Date.now() - lastChange < stallMs) {
    await sleep(250);
    got = await count();
    if (got !== last) {
      last = got;
      lastChange = Date.now();
    }
  }
  return { got, ms: Date.now() - t0 };
}
