/** The machine, the versions and the load a run was measured on, for the results JSON. */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { REPO } from './stack.ts';

const first = (cmd: string, args: string[]): string => {
  try {
    const r = execFileSync(cmd, args, {
      encoding: 'utf8',
      stdio: ['ignore', 'pipe', 'pipe'],
      timeout: 10_000,
    });
    return (
      r
        .split('\n')
        .find((l) => l.trim())
        ?.trim() ?? ''
    );
  } catch (err) {
    // `mosquitto -h` exits 3 after printing its version.
    const out = (err as { stdout?: string }).stdout ?? '';
    return (
      out
        .split('\n')
        .find((l) => l.trim())
        ?.trim() ?? 'unknown'
    );
  }
};

const pkgVersion = (name: string): string => {
  try {
    const p = path.join(REPO, 'node_modules', name, 'package.json');
    return (JSON.parse(fs.readFileSync(p, 'utf8')) as { version: string }).version;
  } catch {
    return 'missing';
  }
};

export function machineInfo() {
  const cpus = os.cpus();
  return {
    hostname: os.hostname(),
    os: `${os.type()} ${os.release()} ${os.arch()}`,
    cores: cpus.length,
    cpuModel: cpus[0]?.model ?? 'unknown',
    cpuMHz: cpus[0]?.speed ?? 0,
    memoryGiB: Math.round((os.totalmem() / 2 ** 30) * 10) / 10,
    loadAverageAtStart: os.loadavg().map((v) => Math.round(v * 100) / 100),
  };
}

export async function versions(influxUrl?: string) {
  let influxd = 'not started';
  if (influxUrl) {
    const res = await fetch(`${influxUrl}/ping`).catch(() => null);
    const v = res?.headers.get('x-influxdb-version') ?? 'unknown';
    // install-deps.sh builds v1.8.10 from source; such a build reports "unknown".
    influxd =
      v === 'unknown' ? '1.8.10 (source build of .tools/bin/influxd; reports "unknown")' : v;
  }
  return {
    node: process.version,
    mosquitto:
      first('mosquitto', ['-h']).replace(/^mosquitto version /, '') ||
      first('/usr/sbin/mosquitto', ['-h']),
    influxd,
    chromium: first('/usr/bin/chromium', ['--version']),
    'mqtt.js': pkgVersion('mqtt'),
    'playwright-core': pkgVersion('playwright-core'),
  };
}
