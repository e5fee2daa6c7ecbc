/**
 * `armtwin gateway --bus dynamixel|feetech` end to end: the simulator answers as a servo bus
 * (`armtwin sim --bus … --serial`) on one side of a socat pty pair, the gateway drives it from
 * the other, and a real Mosquitto carries the frames. Positions come back as angle frames,
 * health as health frames; moves published on MQTT move the emulated servos; `#255PDST!` holds
 * the arm short of a slow move's target; a ±360° joint round-trips +350.00°; `$KMS` goes
 * through the IK; and the gateway
 * survives the line going away and coming back. The profile is armtwin5 with its wrist roll
 * (004) a ±360° bus servo, written to a temporary models folder.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { MODELS_DIR } from '@armtwin/sim';
import { parseSummary } from '@armtwin/protocol';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';
import { serialLine } from './serial-line.ts';

const broker = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-bus-'));
const MODELS = path.join(dir, 'models');
const PROFILE = 'bus5';
const SERVOS = 6;

beforeAll(() => {
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  ) as { name: string; servos: Record<string, unknown>[] };
  raw.name = PROFILE;
  raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
  fs.mkdirSync(path.join(MODELS, PROFILE), { recursive: true });
  fs.writeFileSync(path.join(MODELS, PROFILE, 'profile.json'), JSON.stringify(raw));
});

afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

describe.each(['dynamixel', 'feetech'] as const)('armtwin gateway --bus %s', (bus) => {
  const ARM = `bus-${bus}`;
  const HOST_SIDE = path.join(dir, `${bus}-gateway`);
  const ARM_SIDE = path.join(dir, `${bus}-arm`);
  const profileArgs = ['--profile', PROFILE, '--models', MODELS, '--baud', '1000000'];
  const line = serialLine(
    HOST_SIDE,
    ARM_SIDE,
    (armSide) => ['sim', '--bus', bus, '--serial', armSide, ...profileArgs],
    'simulated servo bus on the serial line',
  );
  let gateway: Child;
  let w: StatusWatcher;
  /** Every status payload as it came, for the exact text of frames. */
  const payloads: string[] = [];

  const startLine = () => line.start();
  const stopLine = () => line.stop();

  /** Servo `id`'s angle in every state group after item `from`. */
  const angles = (id: number, from = 0) => w.angles(id, from, SERVOS);

  const reaches = (id: number, deg: number, from: number, ms = 10_000) =>
    w.until(
      () => (angles(id, from).includes(deg) ? true : undefined),
      ms,
      `servo ${id} at ${deg}°`,
    );

  const online = (value: string) => () =>
    w.retained.get(`arm/${ARM}/online`) === value ? true : undefined;

  beforeAll(async () => {
    await startLine();
    w = await StatusWatcher.connect(broker().url, ARM);
    w.client.on('message', (topic, payload) => {
      if (topic === `arm/${ARM}/status`) payloads.push(payload.toString());
    });
    gateway = armtwin([
      'gateway',
      '--bus',
      bus,
      '--serial',
      HOST_SIDE,
      ...profileArgs,
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
  });

  test('positions come back as $TIM-stamped angle groups, health as health groups', async () => {
    await w.until(() => (angles(0).length >= 5 ? true : undefined), 10_000, 'angle groups');
    const group = payloads.find((p) => p.includes('{#000A'))!;
    expect(group).toMatch(/^\$TIM:\d+!\{#000A\+000\.00!#001A\+000\.00!.*#005A\+000\.00!\}$/);
    const health = await w.until(() => w.health(1), 10_000, 'a health group');
    expect(health.temp).toBe(25);
    expect(health.mv).toBeGreaterThan(5000);
  });

  test('a move on MQTT moves the emulated servo and its angle comes back', async () => {
    const from = w.items.length;
    await w.send('#001A+030.00T0500!');
    await reaches(1, 30, from);
    await w.send('#002P1800T0300!'); // 1800 µs = +40.5° through the profile (§2)
    await reaches(2, 40.5, from);
  });

  test('a ±360° joint round-trips +350.00°; beyond its limit is refused', async () => {
    const from = w.items.length;
    await w.send('#004A+361.00T0100!');
    const refused = await w.frame((f) => f.type === 'controllerError', from);
    expect(refused.frame).toMatchObject({ text: 'limit 004 A361 outside -360..360' });
    await w.send('#004A+350.00T0500!');
    await reaches(4, 350, from);
    expect(payloads.some((p) => p.includes('#004A+350.00!'))).toBe(true);
  });

  test('its summary on arm/{id}/summary: still, the pose in servo degrees, the last $ERR', async () => {
    await w.client.subscribeAsync(`arm/${ARM}/summary`, { qos: 0 });
    const s = await w.until(
      () => {
        const r = parseSummary(w.retained.get(`arm/${ARM}/summary`) ?? '');
        return r.ok && r.summary.state === 'still' ? r.summary : undefined;
      },
      5000,
      'a summary',
    );
    expect(s.joints.find((j) => j.id === 4)).toMatchObject({ min: -360, max: 360 });
    expect(s.joints.find((j) => j.id === 4)!.deg).toBeCloseTo(350, 0);
    expect(s.joints.find((j) => j.id === 1)!.deg).toBeCloseTo(30, 0);
    expect(s.error?.text).toBe('limit 004 A361 outside -360..360');
    expect([s.health, s.holder]).toEqual(['normal', null]);
  });

  test('#255PDST! holds the arm short of a slow move', async () => {
    const from = w.items.length;
    await w.send('#000A+090.00T9000!'); // 10°/s
    await w.until(
      () => (angles(0, from).some((d) => d > 5) ? true : undefined),
      10_000,
      'the base moving',
    );
    await w.send('#255PDST!');
    const still = await w.until(
      () => {
        const recent = angles(0, from).slice(-25);
        return recent.length === 25 && new Set(recent).size === 1 ? recent[0] : undefined;
      },
      10_000,
      'the base to stop',
    );
    expect(still).toBeGreaterThan(5);
    expect(still).toBeLessThan(60);
  });

  test('$KMS goes through the IK: $KMS:0! and the base turns toward the target', async () => {
    const from = w.items.length;
    await w.send('$KMS:150,50,120,800!');
    const r = await w.frame((f) => f.type === 'kmsResult', from);
    expect(r.frame).toMatchObject({ code: 0 });
    const yaw = (Math.atan2(50, 150) * 180) / Math.PI;
    await w.until(
      () => (angles(0, from).some((d) => Math.abs(d - yaw) < 0.1) ? true : undefined),
      5000,
      `the base at ${yaw.toFixed(2)}°`,
    );
  });

  test('survives the line going away and coming back', async () => {
    const mark = w.history.length;
    await stopLine();
    await w.until(
      () =>
        w.history.slice(mark).some((m) => m.topic === `arm/${ARM}/online` && m.payload === '0')
          ? true
          : undefined,
      10_000,
      'online 0 while the line is gone',
    );
    const from = w.items.length;
    await w.send('#001A+010.00T0100!');
    const refused = await w.frame((f) => f.type === 'controllerError', from);
    expect(refused.frame).toMatchObject({ text: 'gateway: serial line down' });
    await startLine();
    await w.until(online('1'), 15_000, 'online 1 again');
    const back = w.items.length;
    await reaches(1, 0, back, 15_000); // a fresh arm, at home
    await w.send('#001A-020.00T0200!');
    await reaches(1, -20, back);
  });
});
