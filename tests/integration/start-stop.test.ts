/**
 * Ctrl-C on `npm start`, as a terminal sends it: SIGINT to the whole foreground process group
 * (npm, node scripts/start.mjs and whatever they started), with npm forwarding it to its child
 * as well. The parts stop in dependency order: the simulated arm goes offline, the middleware
 * writes its last points, then the local influxd stops. Afterwards the spool holds no batch and
 * InfluxDB holds the last state the arm published. Real npm, armtwin up, embedded broker, local
 * influxd (on free ports, data in a temp folder).
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, expect, test } from 'vitest';
import { startLocalInflux } from '@armtwin/middleware';
import { LOOPBACK } from '../helpers/services.ts';
import { startNpm, type NpmStart } from '../helpers/npm-start.ts';
import { StatusWatcher } from './sim-helpers.ts';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-stop-'));
const spoolDir = path.join(dir, 'spool');
const influxDir = path.join(dir, 'influx');
let npm: NpmStart | undefined;

afterAll(() => {
  // Whatever happened, nothing of this test keeps running.
  npm?.kill();
  fs.rmSync(dir, { recursive: true, force: true });
});

/** The newest point time of servo 0 of arm1 in the `armtwin` database, ms (NaN if none). */
async function lastStored(url: string): Promise<number> {
  const q = `SELECT last(pwm) FROM servo WHERE arm='arm1' AND id='000'`;
  const res = await fetch(`${url}/query?db=armtwin&epoch=ms`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  });
  const body = (await res.json()) as { results: { series?: { values: [number, number][] }[] }[] };
  return body.results[0]?.series?.[0]?.values[0]?.[0] ?? NaN;
}

/**
 * What waits in the spool (a folder per InfluxDB destination): sealed batches, and an open
 * journal that has points.
 */
function spooled(): string[] {
  const files = fs.existsSync(spoolDir)
    ? fs.readdirSync(spoolDir, { recursive: true, encoding: 'utf8' })
    : [];
  return files.filter((f) => {
    const full = path.join(spoolDir, f);
    return f.endsWith('.lp') && fs.statSync(full).isFile() && fs.statSync(full).size > 0;
  });
}

test('Ctrl-C on npm start: arm offline, last points written, spool empty, influxd stopped', async () => {
  const up = (npm = await startNpm(dir, ['--no-web']));
  const { exited, mqttPort, influxUrl, influxPort: iPort } = up;

  const deadline = Date.now() + 120_000;
  while (!up.output().includes('middleware: running')) {
    if (Date.now() > deadline || up.hasExited())
      throw new Error(`npm start did not start its middleware:\n${up.output()}`);
    await new Promise((r) => setTimeout(r, 200));
  }
  expect(up.output()).toContain(`storage: InfluxDB at ${influxUrl} (local influxd`);
  // Data flows; its newest points wait in the middleware's open batch (sealed every 5 s).
  const watcher = await StatusWatcher.connect(`mqtt://${LOOPBACK}:${mqttPort}`, 'arm1', {
    reconnectPeriod: 0,
  });
  await watcher.until(() => (watcher.positions(0).length >= 5 ? true : undefined), 10_000, 'state');

  up.interrupt();
  // npm ends the way a Ctrl-C'd script does (by the signal it passed on), after armtwin stopped.
  expect(await exited, up.output()).toBe('SIGINT');
  expect(up.output()).toContain('armtwin: stopped');
  await watcher.close();
  // The arm said so before it stopped publishing, and every part said it stopped.
  expect(watcher.retained.get('arm/arm1/online')).toBe('0');
  expect(up.output()).not.toContain('stopping with batches still spooled');
  expect(fs.existsSync(spoolDir)).toBe(true);
  expect(spooled()).toEqual([]);

  // influxd was stopped by armtwin, not killed by the Ctrl-C: its data opens again, holding the
  // last state the arm published (the middleware saw every sample the watcher saw, and more).
  const published = watcher.positions(0).at(-1)![0];
  const influx = await startLocalInflux({ dataDir: influxDir, port: iPort, log: () => {} });
  expect(influx).not.toBeNull();
  try {
    expect(await lastStored(influxUrl)).toBeGreaterThanOrEqual(published);
  } finally {
    await influx!.stop();
  }
});
