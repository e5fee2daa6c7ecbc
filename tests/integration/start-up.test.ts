/**
 * `npm start` in miniature: `node scripts/start.mjs` (without the middleware, whose local
 * influxd would take the shared port 8086, and without building the HUD) brings up the
 * embedded Aedes broker, the HTTP port with /mqtt and /api, and the simulated arm1; mqtt.js
 * clients reach the arm over TCP and over WebSockets; SIGINT stops it all cleanly.
 */
import mqtt from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freePorts } from '../helpers/services.ts';
import { startUpProcess, StatusWatcher, type Child } from './sim-helpers.ts';

let up: Child;
let httpPort = 0;
let mqttPort = 0;
const watchers: StatusWatcher[] = [];

beforeAll(async () => {
  [httpPort = 0, mqttPort = 0] = await freePorts(2);
  up = await startUpProcess(['scripts/start.mjs'], ['--no-middleware', '--no-web'], {
    httpPort,
    mqttPort,
  });
});

afterAll(async () => {
  await Promise.all(watchers.map((w) => w.close()));
  await up?.stop('SIGKILL');
});

async function watch(url: string) {
  const w = await StatusWatcher.connect(url, 'arm1');
  watchers.push(w);
  return w;
}

describe('npm start (scripts/start.mjs → armtwin up)', () => {
  test('prints the URL to open', () => {
    expect(up.output()).toContain(`open http://127.0.0.1:${httpPort}/`);
  });

  test('the embedded broker serves MQTT over TCP: arm1 is online and streams', async () => {
    const w = await watch(`mqtt://127.0.0.1:${mqttPort}`);
    await w.until(
      () => (w.retained.get('arm/arm1/online') === '1' ? true : undefined),
      10_000,
      'online 1',
    );
    await w.until(() => (w.positions(0).length >= 5 ? true : undefined), 10_000, 'state samples');
  });

  test('and MQTT over WebSockets at /mqtt on the HTTP port, both ways', async () => {
    const w = await watch(`ws://127.0.0.1:${httpPort}/mqtt`);
    await w.until(
      () => (w.positions(0).length >= 5 ? true : undefined),
      10_000,
      'state samples over ws',
    );
    const from = w.items.length;
    await w.send('$PNG:31337!');
    await w.frame((f) => f.type === 'ping' && f.seq === 31337, from);
  });

  test('/api/whoami: the anonymous demo gives everyone the operator role', async () => {
    const res = await fetch(`http://127.0.0.1:${httpPort}/api/whoami`);
    expect(await res.json()).toEqual({ name: '', role: 'operator', anonymous: true });
  });

  test('/api answers even without the middleware (503, JSON)', async () => {
    const res = await fetch(`http://127.0.0.1:${httpPort}/api/healthz`);
    expect(res.status).toBe(503);
    expect(await res.json()).toMatchObject({ ok: false });
  });

  test('SIGINT stops everything cleanly: arm1 goes offline, exit code 0', async () => {
    const client = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`, { reconnectPeriod: 0 });
    const offline = new Promise<string>((resolve) => {
      client.on('message', (topic, payload) => {
        if (topic === 'arm/arm1/online' && payload.toString() === '0') resolve('0');
      });
    });
    await client.subscribeAsync('arm/arm1/online', { qos: 1 });
    const code = up.stop('SIGINT');
    expect(await offline).toBe('0');
    expect(await code).toBe(0);
    expect(up.output()).toContain('stopped');
    await client.endAsync(true);
  });
});
