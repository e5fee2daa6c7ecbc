/**
 * `armtwin gateway` end to end over a pseudo-terminal pair from socat, with the simulated
 * controller (`armtwin sim --serial`) on the far side, through a real Mosquitto: frames both
 * ways, the port disappearing and coming back, the broker restarting.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { OPERATOR_BEAT_MS, parseSummary, type ArmSummary } from '@armtwin/protocol';
import { rawOperator } from '../helpers/raw-operator.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';
import { serialLine } from './serial-line.ts';

const ARM = 'gwtest';
const broker = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-pty-'));
const HOST_SIDE = path.join(dir, 'gateway');
const ARM_SIDE = path.join(dir, 'arm');

const line = serialLine(
  HOST_SIDE,
  ARM_SIDE,
  (armSide) => ['sim', '--serial', armSide, '--rate', '20'],
  'simulated controller on the serial line',
);
let gateway: Child;
let w: StatusWatcher;
let seq = 0;
const startLine = () => line.start();
const stopLine = () => line.stop();

const online = (value: string) => () =>
  w.retained.get(`arm/${ARM}/online`) === value ? true : undefined;
/** `online` was published as `value` at some point after history index `from`. */
const onlineSince = (value: string, from: number) => () =>
  w.history.slice(from).some((m) => m.topic === `arm/${ARM}/online` && m.payload === value)
    ? true
    : undefined;

/** A ping through gateway and line; resent every 2 s (a line just reopened may lose one). */
async function ping(timeoutMs = 10_000) {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const n = ++seq;
    const from = w.items.length;
    await w.send(`$PNG:${n}!`);
    try {
      return await w.frame(
        (f) => f.type === 'ping' && f.seq === n,
        from,
        Math.min(2000, deadline - Date.now()),
      );
    } catch (err) {
      if (Date.now() >= deadline) throw err;
    }
  }
}

beforeAll(async () => {
  await startLine();
  w = await StatusWatcher.connect(broker().url, ARM);
  gateway = armtwin([
    'gateway',
    '--serial',
    HOST_SIDE,
    '--baud',
    '115200',
    '--mqtt',
    broker().url,
    '--arm',
    ARM,
  ]);
  await w.until(online('1'), 20_000, 'online 1');
});

afterAll(async () => {
  await gateway?.stop('SIGKILL');
  await stopLine();
  await w?.close();
  fs.rmSync(dir, { recursive: true, force: true });
});

describe('armtwin gateway over a pty pair', () => {
  test('carries control to the line and stamped status (groups kept) back', async () => {
    const echo = await ping();
    expect(echo.time).toBeGreaterThan(1.7e12);
    const from = w.items.length;
    await w.send('#000P1600T0200!{#001PRAD!#002PRAD!}');
    await w.until(
      () => w.positions(0, from).find(([, p]) => p === 1600),
      5000,
      'servo 000 at 1600',
    );
    const reads = await w.until(() => {
      for (const it of w.items.slice(from)) {
        if ('group' in it && it.group.frames.length === 2) return it;
      }
      return undefined;
    });
    expect(reads.group.frames).toEqual([
      { type: 'position', id: 1, pwm: 1500, time: reads.time },
      { type: 'position', id: 2, pwm: 1500, time: reads.time },
    ]);
    await w.until(() => w.health(0), 5000, 'a health group');
    const stamps = w.positions(0, from).map(([t]) => t);
    expect(stamps.every((t) => t > 1.7e12)).toBe(true);
  });

  test('deadman: a beating operator goes silent mid-move; the gateway writes #255PDST! on its lease, before the will', async () => {
    const operatorTopic = `arm/${ARM}/operator`;
    await w.client.subscribeAsync(operatorTopic, { qos: 1 });
    const start = w.items.length;
    await w.send('#000P1000T0300!');
    await w.until(() => w.positions(0, start).find(([, p]) => p === 1000), 5000, 'P1000');
    const raw = await rawOperator({
      port: broker().port,
      armId: ARM,
      keepaliveS: 2,
      beatMs: OPERATOR_BEAT_MS,
    });
    try {
      await new Promise((r) => setTimeout(r, 3 * OPERATOR_BEAT_MS));
      const from = w.items.length;
      await w.send('#000P2500T9000!'); // 9 s
      await w.until(() => w.positions(0, from).find(([, p]) => p > 1100), 5000, 'the base moving');
      const willFrom = w.history.length;
      const will = () =>
        w.history.slice(willFrom).some((m) => m.topic === operatorTopic && m.payload === '0');
      raw.silence();
      // Stopped: the last half second of samples holds one pulse, well short of the target.
      const still = await w.until(
        () => {
          const recent = w.positions(0, from).slice(-10);
          return recent.length === 10 && new Set(recent.map(([, p]) => p)).size === 1
            ? recent[0]![1]
            : undefined;
        },
        15_000,
        'the base to stop',
      );
      expect(will(), 'stopped by the lease, not by the broker’s will').toBe(false);
      expect(still).toBeLessThan(2400);
      await w.until(() => (will() ? true : undefined), 15_000, 'the will, in the end');
    } finally {
      raw.close();
    }
  });

  test('one operator at a time: a non-holder’s move never reaches the line; the holder’s does', async () => {
    const holder = `arm/${ARM}/holder`;
    await w.client.subscribeAsync(holder, { qos: 1 });
    const heldBy = (user: string | null) => () =>
      (JSON.parse(w.retained.get(holder) ?? '{}') as { user?: string | null }).user === user
        ? true
        : undefined;
    await w.until(heldBy(null), 5000, 'nobody holding');
    await w.client.publishAsync(`arm/${ARM}/claim/alice`, 'take', { qos: 1 });
    await w.until(heldBy('alice'), 5000, 'alice holding');
    try {
      const from = w.items.length;
      await w.client.publishAsync(`arm/${ARM}/control/bob`, '#000P1900T0200!', { qos: 1 });
      await w.send('#000P1900T0200!'); // the plain topic is "someone else" while alice holds
      await w.frame((f) => f.type === 'controllerError' && f.text === 'controlled by alice', from);
      await w.client.publishAsync(`arm/${ARM}/control/alice`, '#000P1200T0200!', { qos: 1 });
      await w.until(() => w.positions(0, from).find(([, p]) => p === 1200), 5000, 'P1200');
      expect(w.positions(0, from).some(([, p]) => p > 1600)).toBe(false);
    } finally {
      await w.client.publishAsync(`arm/${ARM}/claim/alice`, 'release', { qos: 1 });
      await w.until(heldBy(null), 5000, 'released');
    }
  });

  test('survives the port disappearing and coming back', async () => {
    const mark = w.history.length;
    await stopLine();
    await w.until(onlineSince('0', mark), 10_000, 'online 0 while the line is gone');
    const from = w.items.length;
    await w.send('$PNG:1!');
    const refused = await w.frame((f) => f.type === 'controllerError', from);
    expect(refused.frame).toMatchObject({ text: 'gateway: serial line down' });
    await startLine();
    await w.until(online('1'), 15_000, 'online 1 again');
    await ping();
  });

  test('survives the broker restarting', async () => {
    await broker().restart();
    await w.until(() => (w.client.connected ? true : undefined), 15_000, 'watcher reconnected');
    await w.client.subscribeAsync([`arm/${ARM}/status`, `arm/${ARM}/online`], { qos: 1 });
    await w.until(online('1'), 15_000, 'online 1 after the restart');
    await ping(15_000);
  });

  test('its summary on arm/{id}/summary: who holds it, the pose the firmware reports', async () => {
    const topic = `arm/${ARM}/summary`;
    await w.client.subscribeAsync(topic, { qos: 0 });
    const summary = (ok: (s: ArmSummary) => boolean) => () => {
      const r = parseSummary(w.retained.get(topic) ?? '');
      return r.ok && ok(r.summary) ? r.summary : undefined;
    };
    await w.client.publishAsync(`arm/${ARM}/claim/carol`, 'take', { qos: 1 });
    try {
      await w.until(
        summary((x) => x.holder === 'carol'),
        5000,
        'carol holding',
      );
      // Servo 000 to 1200 µs, about 27° from the middle, as the firmware then reports.
      await w.client.publishAsync(`arm/${ARM}/control/carol`, '#000P1200T0200!', { qos: 1 });
      await w.until(
        summary((x) => x.state === 'still' && Math.abs(x.joints[0]?.deg ?? 0) > 20),
        5000,
        'servo 000 away from the middle in the summary',
      );
    } finally {
      await w.client.publishAsync(`arm/${ARM}/claim/carol`, 'release', { qos: 1 });
    }
    await w.until(
      summary((x) => x.holder === null),
      5000,
      'nobody holding again',
    );
  });

  test('on SIGTERM it publishes online 0 and exits 0', async () => {
    w.retained.delete(`arm/${ARM}/online`);
    expect(await gateway.stop('SIGTERM')).toBe(0);
    await w.until(online('0'), 5000, 'online 0');
  });
});
