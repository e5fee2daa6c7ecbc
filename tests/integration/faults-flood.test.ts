/**
 * "Malformed flood": 10 000 malformed frames per second for 10 s (100 QoS 1 messages
 * of 100 frames each per second, from mqtt.js in this process) at the middleware, then at the
 * simulated arm. Each stays responsive (/healthz answers and a valid frame sent mid-flood is
 * stored; a ping sent mid-flood is echoed), its memory stays bounded, and every malformed
 * frame is counted: the sum of the rejection counters equals what was sent.
 */
import fs from 'node:fs';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, expect, test } from 'vitest';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { select } from '../../apps/middleware/test/support/harness.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const broker = useMosquitto({ extraConfig: ['max_queued_messages 100000'] });
const influx = useInflux();
const mws = useMiddlewares('mw-flood', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

/** Five malformed frames, each dropped and counted exactly once by the protocol reader. */
const UNIT = '#000P9999!#00AP1500!$XYZ:1!#001T999V99999!$KMS:a,b!';
const FRAMES_PER_MESSAGE = 100;
const PAYLOAD = UNIT.repeat(FRAMES_PER_MESSAGE / 5);
const RATE = 10_000; // frames/s
const SECONDS = 10;
const TICK_MS = 100;
const SENT = RATE * SECONDS;

let sim: Child | undefined;
const clients: MqttClient[] = [];

afterAll(async () => {
  await Promise.all(clients.map((c) => c.endAsync(true)));
  await sim?.stop();
});

/** RSS (bytes) and CPU time (s) of a process, from /proc. */
function proc(pid: number): { rss: number; cpu: number } {
  const status = fs.readFileSync(`/proc/${pid}/status`, 'utf8');
  const rss = Number(/VmRSS:\s+(\d+) kB/.exec(status)![1]) * 1024;
  const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
  const f = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
  return { rss, cpu: (Number(f[11]) + Number(f[12])) / 100 };
}

/** Sends the flood; `during(second)` runs once per second, concurrently. */
async function flood(topic: string, during: (s: number) => Promise<void>): Promise<number> {
  // A client id of its own per flood: two clients with one id would kick each other off.
  const pub = await mqtt.connectAsync(broker().url, {
    clientId: `flood-${topic.split('/')[2]}-${process.pid}`,
  });
  let reconnects = 0;
  pub.on('reconnect', () => reconnects++);
  let sent = 0;
  const checks: Promise<void>[] = [];
  const t0 = Date.now();
  const perTick = (RATE * TICK_MS) / 1000 / FRAMES_PER_MESSAGE;
  for (let k = 0; k < (SECONDS * 1000) / TICK_MS; k++) {
    const wait = t0 + k * TICK_MS - Date.now();
    if (wait > 0) await sleep(wait);
    for (let i = 0; i < perTick; i++) pub.publish(topic, PAYLOAD, { qos: 1 });
    sent += perTick * FRAMES_PER_MESSAGE;
    if ((k * TICK_MS) % 1000 === 0) checks.push(during((k * TICK_MS) / 1000));
  }
  await Promise.all(checks);
  for (let i = 0; i < 300 && Object.keys(pub.outgoing).length > 0; i++) await sleep(100); // all PUBACKed
  expect(reconnects).toBe(0); // no reconnect, so no QoS 1 redelivery doubles a frame
  await pub.endAsync();
  return sent;
}

const rejectedSum = (m: Record<string, number>) =>
  Object.entries(m)
    .filter(([k]) => k.startsWith('frames_rejected_total'))
    .reduce((a, [, v]) => a + v, 0);

test(
  'middleware: 10 000 malformed frames/s for 10 s: responsive, bounded, every frame counted',
  { timeout: 120_000 },
  async () => {
    const mw = await mws.spawn({
      env: {
        FLUSH_INTERVAL_MS: '500',
      },
    });
    const pid = mw.child.pid!;
    await sleep(1000);
    const before = proc(pid);
    const healthMs: number[] = [];
    const t0 = Date.now();
    const sent = await flood('arm/flood/status', async (s) => {
      const start = Date.now();
      const h = await mw!.health();
      healthMs.push(Date.now() - start);
      expect(h.status).toBe(200);
      if (s === 5) {
        const valid = await mqtt.connectAsync(broker().url);
        clients.push(valid);
        await valid.publishAsync('arm/flood/status', `$TIM:${Date.UTC(2026, 3, 1)}!#003P1234!`, {
          qos: 1,
        });
      }
    });
    expect(sent).toBe(SENT);
    let m = await mw.metrics();
    const deadline = Date.now() + 30_000;
    while (rejectedSum(m) < SENT && Date.now() < deadline) {
      await sleep(250);
      m = await mw.metrics();
    }
    const wall = (Date.now() - t0) / 1000;
    const after = proc(pid);
    expect(rejectedSum(m)).toBe(SENT);
    expect(m['frames_rejected_total{reason="out-of-range"}']).toBe(SENT * 0.4);
    expect(m['frames_rejected_total{reason="malformed"}']).toBe(SENT * 0.6);
    let rows: unknown[][] = [];
    for (let i = 0; i < 40 && rows.length === 0; i++) {
      rows = await select(
        { url: influx().url, db: influx().db },
        `SELECT pwm FROM servo WHERE arm = 'flood'`,
      );
      if (rows.length === 0) await sleep(250);
    }
    expect(rows.map((r) => r[1])).toEqual([1234]);
    expect(after.rss - before.rss).toBeLessThan(150 * 1024 * 1024);
    console.log(
      `middleware flood: RSS ${(before.rss / 2 ** 20).toFixed(1)} → ${(after.rss / 2 ** 20).toFixed(1)} MiB; ` +
        `CPU ${(after.cpu - before.cpu).toFixed(2)} s over ${wall.toFixed(1)} s ` +
        `(${((100 * (after.cpu - before.cpu)) / wall).toFixed(0)} % of a core); ` +
        `/healthz max ${Math.max(...healthMs)} ms`,
    );
  },
);

test(
  'sim: 10 000 malformed frames/s for 10 s on control: pings answered, bounded, every frame counted',
  { timeout: 120_000 },
  async () => {
    sim = armtwin(['sim', '--mqtt', broker().url, '--arm', 'flood', '--rate', '50'], {
      LOG_LEVEL: 'info',
    });
    const w = await StatusWatcher.connect(broker().url, 'flood');
    clients.push(w.client);
    await w.until(
      () => (w.retained.get('arm/flood/online') === '1' ? true : undefined),
      15_000,
      'sim online',
    );
    const pid = sim.proc.pid!;
    await sleep(500);
    const before = proc(pid);
    const t0 = Date.now();
    const pingMs: number[] = [];
    const sent = await flood('arm/flood/control', async (s) => {
      if (s % 2 !== 1) return;
      const from = w.items.length;
      const start = Date.now();
      await w.send(`$PNG:${1000 + s}!`);
      await w.frame((f) => f.type === 'ping' && f.seq === 1000 + s, from, 10_000);
      pingMs.push(Date.now() - start);
    });
    await sleep(2000); // let the broker deliver what is still queued
    const after = proc(pid);
    const wall = (Date.now() - t0) / 1000;
    expect(await sim.stop()).toBe(0);
    const stopped = sim
      .output()
      .split('\n')
      .find((l) => l.includes('"sim stopped"'));
    expect(stopped, sim.output().slice(-2000)).toBeDefined();
    const counters = JSON.parse(stopped!).counters as { rejected: Record<string, number> };
    const sum = Object.values(counters.rejected).reduce((a, b) => a + b, 0);
    expect(sent).toBe(SENT);
    expect(sum).toBe(SENT);
    expect(pingMs).toHaveLength(5);
    expect(after.rss - before.rss).toBeLessThan(150 * 1024 * 1024);
    console.log(
      `sim flood: RSS ${(before.rss / 2 ** 20).toFixed(1)} → ${(after.rss / 2 ** 20).toFixed(1)} MiB; ` +
        `CPU ${(after.cpu - before.cpu).toFixed(2)} s over ${wall.toFixed(1)} s ` +
        `(${((100 * (after.cpu - before.cpu)) / wall).toFixed(0)} % of a core); ping round trips ${pingMs.join(', ')} ms`,
    );
  },
);
