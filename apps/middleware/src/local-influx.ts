/**
 * `startLocalInflux({ dataDir })`: the project's own influxd 1.8 for `npm start` when no
 * INFLUX_URL is given. Makes `.tools/bin/influxd` (scripts/build-influxd.sh) first when it is missing and Go is
 * on PATH; runs it on 127.0.0.1 with Flux on and usage reporting off; returns null (and why)
 * when that is impossible.
 */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const REPO_ROOT = path.resolve(
  path.dirname(fileURLToPath(import.meta.url)),
  '..',
  '..',
  '..',
);
export const LOCAL_INFLUXD = path.join(REPO_ROOT, '.tools', 'bin', 'influxd');
export const INFLUXD_MODULE = 'github.com/influxdata/influxdb/cmd/influxd@v1.8.10';

export interface LocalInfluxOptions {
  /** Where influxd keeps meta, data and wal. */
  dataDir: string;
  /** HTTP port (default 8086); the RPC port is port + 2. */
  port?: number;
  /** Database created at start; the bucket is `<db>/autogen`. */
  db?: string;
  /** How long to wait for /ping, ms. */
  startTimeoutMs?: number;
  log?: (msg: string) => void;
}

export const DEFAULT_LOCAL_INFLUX_OPTIONS = {
  port: 8086,
  db: 'armtwin',
  startTimeoutMs: 60_000,
} as const;

export interface LocalInflux {
  url: string;
  bucket: string;
  pid: number;
  stop(): Promise<void>;
}

function hasGo(): boolean {
  return spawnSync('go', ['version'], { stdio: 'ignore' }).status === 0;
}

/**
 * Makes `.tools/bin/influxd` with scripts/build-influxd.sh (built once per machine with
 * `go install` into ~/.cache/armtwin, minutes; linked after); returns an error text or null.
 */
export function buildInfluxd(log: (m: string) => void): string | null {
  if (!hasGo()) return 'Go is not on PATH, so influxd cannot be built';
  log(`making ${LOCAL_INFLUXD} (${INFLUXD_MODULE}); a first build takes a few minutes`);
  const r = spawnSync('bash', [path.join(REPO_ROOT, 'scripts', 'build-influxd.sh')], {
    stdio: ['ignore', 'ignore', 'pipe'],
    encoding: 'utf8',
  });
  if (r.status !== 0)
    return `building influxd failed: ${(r.stderr ?? '').trim().split('\n').slice(-3).join(' / ')}`;
  return fs.existsSync(LOCAL_INFLUXD) ? null : 'the build finished but produced no influxd';
}

/**
 * The influxd 1.8 configuration armtwin runs with (here and in the test helper): Flux on,
 * usage reporting off, loopback only, everything under `dir`.
 */
export function influxdConf(dir: string, httpPort: number, rpcPort: number, extra = ''): string {
  return `reporting-disabled = true
bind-address = "127.0.0.1:${rpcPort}"
[meta]
  dir = "${dir}/meta"
[data]
  dir = "${dir}/data"
  wal-dir = "${dir}/wal"
  query-log-enabled = false
[http]
  enabled = true
  bind-address = "127.0.0.1:${httpPort}"
  auth-enabled = false
  log-enabled = false
  flux-enabled = true
[monitor]
  store-enabled = false
[continuous_queries]
  enabled = false
${extra}
`;
}

/**
 * Starts the local influxd; null when impossible, after telling `log` why (the caller
 * then runs without storage and says so).
 */
export async function startLocalInflux(options: LocalInfluxOptions): Promise<LocalInflux | null> {
  const o = { ...DEFAULT_LOCAL_INFLUX_OPTIONS, ...options };
  const log = o.log ?? ((m: string) => console.error(m));
  const unavailable = (why: string) => (log(`no local InfluxDB: ${why}`), null);
  if (!fs.existsSync(LOCAL_INFLUXD)) {
    const why = buildInfluxd(log);
    if (why) return unavailable(`${LOCAL_INFLUXD} is missing and ${why}`);
  }
  const dataDir = path.resolve(o.dataDir);
  fs.mkdirSync(dataDir, { recursive: true });
  const confFile = path.join(dataDir, 'influxd.conf');
  fs.writeFileSync(confFile, influxdConf(dataDir, o.port, o.port + 2));
  const logFd = fs.openSync(path.join(dataDir, 'influxd.log'), 'a');
  // A process group of its own: a terminal's Ctrl-C (SIGINT to the whole foreground group)
  // reaches armtwin only, which stops influxd itself after the middleware's last flush.
  const child: ChildProcess = spawn(LOCAL_INFLUXD, ['run', '-config', confFile], {
    stdio: ['ignore', logFd, logFd],
    detached: true,
  });
  fs.closeSync(logFd);
  // Out of the group, it would outlive a parent that exits without calling stop().
  const stopOnExit = () => child.kill('SIGTERM');
  process.once('exit', stopOnExit);
  let exited = false;
  const exit = new Promise<void>((resolve) =>
    child.once('exit', () => {
      exited = true;
      process.removeListener('exit', stopOnExit);
      resolve();
    }),
  );
  const url = `http://127.0.0.1:${o.port}`;
  const deadline = Date.now() + o.startTimeoutMs;
  while (true) {
    if (exited)
      return unavailable(`influxd exited at start; see ${path.join(dataDir, 'influxd.log')}`);
    const up = await fetch(`${url}/ping`, { signal: AbortSignal.timeout(1000) }).then(
      (r) => r.status === 204,
      () => false,
    );
    if (up) break;
    if (Date.now() > deadline) {
      child.kill('SIGKILL');
      return unavailable(
        `influxd did not answer /ping on ${url} within ${o.startTimeoutMs} ms (port taken?)`,
      );
    }
    await new Promise((r) => setTimeout(r, 200));
  }
  await fetch(`${url}/query`, {
    method: 'POST',
    body: new URLSearchParams({ q: `CREATE DATABASE "${o.db}"` }),
  });
  return {
    url,
    bucket: `${o.db}/autogen`,
    pid: child.pid ?? 0,
    async stop() {
      if (exited) return;
      child.kill('SIGTERM');
      const t = setTimeout(() => child.kill('SIGKILL'), 10_000);
      await exit;
      clearTimeout(t);
    },
  };
}
