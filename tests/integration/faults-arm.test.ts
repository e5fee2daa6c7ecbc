/**
 * Issue 7's faults around the arm, on real Mosquitto with `armtwin sim` as a child process:
 * - broker restart: the simulated arm and the middleware reconnect by themselves, and the arm
 *   says `online 1` again;
 * - simulator killed (SIGKILL): the retained `online` becomes `0` from its last will;
 * - deadman: an operator holding `arm/{id}/operator` (will `0`) goes silent mid-move: the
 *   broker publishes the will after 1.5 × its keep-alive and the arm stops where it is.
 */
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import mqtt from 'mqtt';
import { generate } from 'mqtt-packet';
import { afterAll, describe, expect, test } from 'vitest';
import { freePort } from '../helpers/ports.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import {
  middlewareEnv,
  spawnMiddleware,
  tempDir,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';
import { startBroker } from '../../apps/cli/src/broker/broker.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const broker = useMosquitto();
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
const children: Child[] = [];
const watchers: StatusWatcher[] = [];
let dir = '';
let mw: MiddlewareProcess | undefined;

afterAll(async () => {
  await Promise.all(watchers.map((w) => w.close()));
  await Promise.all(children.map((c) => c.stop('SIGKILL')));
  await mw?.stop();
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
});

async function startSim(arm: string): Promise<{ sim: Child; w: StatusWatcher }> {
  const sim = armtwin(['sim', '--mqtt', broker().url, '--arm', arm, '--rate', '50']);
  children.push(sim);
  const w = await StatusWatcher.connect(broker().url, arm);
  watchers.push(w);
  await w.until(
    () => (w.retained.get(`arm/${arm}/online`) === '1' ? true : undefined),
    15_000,
    'online 1',
  );
  return { sim, w };
}

const online = (w: StatusWatcher, arm: string, v: string) =>
  w.until(
    () => (w.retained.get(`arm/${arm}/online`) === v ? true : undefined),
    15_000,
    `online ${v}`,
  );

describe('faults', () => {
  test(
    'broker restart: the arm and the middleware reconnect by themselves',
    { timeout: 90_000 },
    async () => {
      dir = tempDir('faults-arm');
      mw = await spawnMiddleware(
        middlewareEnv({ mqttUrl: broker().url }, 'mw-faults', dir),
        await freePort(),
        path.join(dir, 'middleware.log'),
      );
      const { w } = await startSim('br1');
      let statusBefore = 0;
      for (let i = 0; i < 40 && statusBefore === 0; i++) {
        await sleep(250);
        statusBefore = (await mw.metrics())['messages_total{topic="status"}'] ?? 0;
      }
      expect(statusBefore).toBeGreaterThan(0);
      w.retained.delete('arm/br1/online');
      await broker().restart();
      const restartedAt = Date.now();
      await online(w, 'br1', '1'); // published again by the arm on reconnect
      const from = w.items.length;
      await w.until(
        () => (w.positions(0, from).length >= 5 ? true : undefined),
        15_000,
        'state after restart',
      );
      const gapMs = Date.now() - restartedAt;
      let m = await mw.metrics();
      for (
        let i = 0;
        i < 60 && !(m['mqtt_connects_total']! >= 2 && m['mqtt_connected'] === 1);
        i++
      ) {
        await sleep(250);
        m = await mw.metrics();
      }
      expect(m['mqtt_connects_total']).toBeGreaterThanOrEqual(2);
      expect(m['mqtt_connected']).toBe(1);
      const statusAfter = m['messages_total{topic="status"}']!;
      await sleep(1000);
      expect((await mw.metrics())['messages_total{topic="status"}']).toBeGreaterThan(statusAfter);
      console.log(`broker restart: the arm streamed again ${gapMs} ms after the broker came back`);
    },
  );

  test(
    'simulator killed: retained online becomes 0 from its last will',
    { timeout: 60_000 },
    async () => {
      const { sim, w } = await startSim('kill1');
      await sim.stop('SIGKILL');
      await online(w, 'kill1', '0');
      const late = await StatusWatcher.connect(broker().url, 'kill1'); // a HUD opened afterwards
      watchers.push(late);
      await online(late, 'kill1', '0');
    },
  );

  test(
    'deadman on Mosquitto 2.0: the operator goes silent mid-move; its will stops the arm',
    { timeout: 60_000 },
    async () => {
      // Mosquitto 2.0 checks keep-alives only every 6 s, on whole seconds: measured 4.6–8.6 s for
      // a 2 s keep-alive (1.5 × 2 s = 3 s). The bound is 1.5 × keep-alive + 1 s + its 6 s period.
      const ms = await deadman(broker().url, broker().port, 'dm1');
      expect(ms).toBeLessThanOrEqual(1.5 * KEEPALIVE_S * 1000 + 7000 + 1000);
      console.log(
        `deadman (Mosquitto): arm stopped ${ms} ms after the operator went silent (keep-alive ${KEEPALIVE_S} s)`,
      );
    },
  );

  test(
    'deadman on the embedded broker: stops within 1.5 × keep-alive',
    { timeout: 60_000 },
    async () => {
      const aedes = await startBroker({ port: 0 });
      try {
        const ms = await deadman(aedes.url, aedes.port, 'dm2');
        expect(ms).toBeLessThanOrEqual(1.5 * KEEPALIVE_S * 1000 + 500);
        console.log(
          `deadman (embedded): arm stopped ${ms} ms after the operator went silent (keep-alive ${KEEPALIVE_S} s)`,
        );
      } finally {
        await aedes.close();
      }
    },
  );
});

const KEEPALIVE_S = 2;

/**
 * An operator holding `arm/{arm}/operator` (will `0`) jogs servo 000 over 9 s and goes silent
 * with its TCP connection open (a frozen page, a pulled cable): a raw MQTT client, so nothing
 * answers for it. Returns the ms from its silence to the arm's `$ERR:deadman stop!`, after
 * checking the arm really stopped on the way.
 */
async function deadman(url: string, port: number, arm: string): Promise<number> {
  const sim = armtwin(['sim', '--mqtt', url, '--arm', arm, '--rate', '50']);
  children.push(sim);
  const w = await StatusWatcher.connect(url, arm);
  watchers.push(w);
  await online(w, arm, '1');
  const sock = net.connect(port, '127.0.0.1');
  await new Promise((r) => sock.once('connect', r));
  sock.on('data', () => {});
  sock.on('error', () => {});
  sock.write(
    generate({
      cmd: 'connect',
      protocolId: 'MQTT',
      protocolVersion: 4,
      clean: true,
      clientId: `hud-operator-${arm}`,
      keepalive: KEEPALIVE_S,
      will: { topic: `arm/${arm}/operator`, payload: Buffer.from('0'), qos: 1, retain: true },
    }),
  );
  sock.write(
    generate({
      cmd: 'publish',
      topic: `arm/${arm}/operator`,
      payload: Buffer.from('1'),
      qos: 0,
      retain: true,
      dup: false,
    }),
  );
  const silentAt = Date.now();
  const op = await mqtt.connectAsync(url);
  const from = w.items.length;
  await op.publishAsync(`arm/${arm}/control`, '#000P2500T9000!', { qos: 1 }); // a 9 s jog
  const err = await w.frame(
    (f) => f.type === 'controllerError' && f.text === 'deadman stop',
    from,
    15_000,
  );
  await sleep(1000);
  const last = w
    .positions(0)
    .slice(-20)
    .map(([, p]) => p);
  expect(new Set(last).size).toBe(1); // not moving
  expect(last[0]).toBeGreaterThan(1500);
  expect(last[0]).toBeLessThan(2500); // stopped on the way, long before the 9 s were up
  expect(w.retained.get(`arm/${arm}/operator`) ?? '0').toBe('0');
  sock.destroy();
  await op.endAsync(true);
  await sim.stop();
  return err.time - silentAt;
}
