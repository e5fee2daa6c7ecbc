/**
 * A throwaway InfluxDB 1.8 (`.tools/bin/influxd`, built by scripts/install-deps.sh): HTTP
 * and RPC on free ports of 127.0.0.1, data in its temp dir, Flux on, usage reporting and
 * request logging off, database `armtwin` created. In 1.8's v2-compatible API the bucket is
 * `armtwin/autogen`, the org is '' and the token is '' (auth is off).
 */
import fs from 'node:fs';
import path from 'node:path';
import { LOOPBACK } from './ports.ts';
import { REPO_ROOT } from './files.ts';
import { startService, type ServiceLifecycle, type ServiceProcess } from './process.ts';
import { influxdConf } from '../../apps/middleware/src/local-influx.ts';

/** The influxd that install-deps.sh builds (resolved from the repo root, not the cwd). */
export const INFLUXD = path.join(REPO_ROOT, '.tools', 'bin', 'influxd');

export interface InfluxOptions {
  /** Database created at start. */
  db?: string;
  /** Milliseconds to wait for `/ping` to answer 204. */
  startTimeoutMs?: number;
  /** Extra influxd.conf text, appended after the generated config. */
  extraConfig?: string;
}

export const DEFAULT_INFLUX_OPTIONS: Required<InfluxOptions> = {
  db: 'armtwin',
  startTimeoutMs: 60_000,
  extraConfig: '',
};

export interface InfluxService extends ServiceLifecycle {
  /** `http://127.0.0.1:<port>` */
  url: string;
  port: number;
  db: string;
  /** `<db>/autogen`, the bucket name for the v2 API. */
  bucket: string;
  org: '';
  token: '';
  // The temp dir holds config, meta, data, wal and log; data survives stop() and kill().
}

async function ping(url: string): Promise<boolean> {
  const res = await fetch(`${url}/ping`, { signal: AbortSignal.timeout(1000) });
  return res.status === 204;
}

/** Runs an InfluxQL statement with POST /query; throws on an HTTP or statement error. */
export async function influxQuery(url: string, q: string): Promise<unknown> {
  const res = await fetch(`${url}/query`, { method: 'POST', body: new URLSearchParams({ q }) });
  const body = (await res.json()) as { error?: string; results?: { error?: string }[] };
  const error = body.error ?? body.results?.find((r) => r.error)?.error;
  if (!res.ok || error) throw new Error(`influx query "${q}" failed: ${res.status} ${error ?? ''}`);
  return body;
}

/** Starts a throwaway influxd, waits for /ping, creates the database. */
export async function startInflux(opts: InfluxOptions = {}): Promise<InfluxService> {
  const o = { ...DEFAULT_INFLUX_OPTIONS, ...opts };
  if (!fs.existsSync(INFLUXD)) throw new Error(`${INFLUXD} not found; run scripts/install-deps.sh`);
  let url = '';
  const proc: ServiceProcess = await startService('influxd', 2, (dir, ports) => {
    const [httpPort = 0, rpcPort = 0] = ports;
    url = `http://${LOOPBACK}:${httpPort}`;
    const confFile = path.join(dir, 'influxd.conf');
    fs.writeFileSync(confFile, influxdConf(dir, httpPort, rpcPort, o.extraConfig));
    const pingUrl = url;
    return {
      name: 'influxd',
      command: INFLUXD,
      args: ['run', '-config', confFile],
      dir,
      host: LOOPBACK,
      ports: [httpPort],
      startTimeoutMs: o.startTimeoutMs,
      ready: () => ping(pingUrl),
    };
  });
  const start = async () => {
    await proc.start();
    await influxQuery(url, `CREATE DATABASE "${o.db}"`);
  };
  try {
    await influxQuery(url, `CREATE DATABASE "${o.db}"`);
  } catch (err) {
    await proc.dispose({ keepLogs: true });
    throw err;
  }
  return {
    url,
    port: proc.spec.ports[0] ?? 0,
    db: o.db,
    bucket: `${o.db}/autogen`,
    org: '',
    token: '',
    dir: proc.spec.dir,
    confFile: path.join(proc.spec.dir, 'influxd.conf'),
    logFile: proc.logFile,
    get running() {
      return proc.running;
    },
    start,
    stop: () => proc.stop(),
    restart: async () => {
      await proc.stop();
      await start();
    },
    kill: () => proc.kill(),
    dispose: (d) => proc.dispose(d),
  };
}

/** The environment an `armtwin` command (export, the middleware) reads a test's influxd with. */
export const influxCliEnv = (influx: { url: string; bucket: string }): NodeJS.ProcessEnv => ({
  ...process.env,
  INFLUX_URL: influx.url,
  INFLUX_BUCKET: influx.bucket,
  INFLUX_TOKEN: '',
  INFLUX_ORG: '',
});
