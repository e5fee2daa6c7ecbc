/**
 * A throwaway InfluxDB 2.7 (`.tools/bin/influxd2`, built by scripts/build-influxd2.sh from its Go
 * module, no UI): HTTP on a free port of 127.0.0.1, bolt and engine files in its temp dir, usage
 * reporting off, then set up through `POST /api/v2/setup` with an org, the bucket `armtwin` and
 * an operator token. Auth is on, as on every real 2.x install: clients send the token.
 */
import fs from 'node:fs';
import path from 'node:path';
import { LOOPBACK } from './ports.ts';
import { REPO_ROOT } from './files.ts';
import { startService } from './process.ts';

export const INFLUXD2 = path.join(REPO_ROOT, '.tools', 'bin', 'influxd2');

export interface Influx2Service {
  /** `http://127.0.0.1:<port>` */
  url: string;
  org: string;
  bucket: string;
  token: string;
  logFile: string;
  dispose(opts?: { keepLogs?: boolean }): Promise<string | undefined>;
}

export const INFLUX2_SETUP = {
  username: 'armtwin',
  password: 'armtwin-test-password',
  org: 'armtwin',
  bucket: 'armtwin',
  token: 'armtwin-test-token',
} as const;

async function health(url: string): Promise<boolean> {
  const res = await fetch(`${url}/health`, { signal: AbortSignal.timeout(1000) });
  return res.ok;
}

export async function startInflux2(): Promise<Influx2Service> {
  if (!fs.existsSync(INFLUXD2))
    throw new Error(`${INFLUXD2} not found; run scripts/install-deps.sh (it builds InfluxDB 2.7)`);
  let url = '';
  const proc = await startService('influxd2', 1, (dir, [port = 0]) => {
    url = `http://${LOOPBACK}:${port}`;
    const base = url;
    return {
      name: 'influxd2',
      command: INFLUXD2,
      args: [
        '--bolt-path',
        path.join(dir, 'influxd.bolt'),
        '--engine-path',
        path.join(dir, 'engine'),
        '--sqlite-path',
        path.join(dir, 'influxd.sqlite'),
        '--http-bind-address',
        `${LOOPBACK}:${port}`,
        '--reporting-disabled',
        '--log-level',
        'warn',
      ],
      dir,
      host: LOOPBACK,
      ports: [port],
      startTimeoutMs: 60_000,
      ready: () => health(base),
    };
  });
  const res = await fetch(`${url}/api/v2/setup`, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(INFLUX2_SETUP),
  });
  if (res.status !== 201) {
    const kept = await proc.dispose({ keepLogs: true });
    throw new Error(`influxd 2.7 setup: ${res.status} ${await res.text()} (logs in ${kept})`);
  }
  return {
    url,
    org: INFLUX2_SETUP.org,
    bucket: INFLUX2_SETUP.bucket,
    token: INFLUX2_SETUP.token,
    logFile: proc.logFile,
    dispose: (d) => proc.dispose(d),
  };
}
