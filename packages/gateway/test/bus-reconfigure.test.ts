/**
 * A new calibration put in force while the bus gateway runs (`BusGatewayCore.reconfigure`, what
 * the profile file watch calls): the same shaft reads the other way round after a polarity flip,
 * goals are written the new way, nothing moves and torque stays on; a profile of other servos is
 * refused and changes nothing.
 */
import fs from 'node:fs';
import path from 'node:path';
import { expect, test } from 'vitest';
import { parseProfile, type Profile } from '@armtwin/robot';
import { createReader } from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { createEmulatedBus } from '@armtwin/servo-bus';
import { BusGatewayCore, BUS_MODELS_DIR } from '../src/index.ts';

/** armtwin5 with its wrist roll (004) a bus servo of this polarity. */
function profile(polarity: 1 | -1, servos = 6, limit = 180): Profile {
  const raw = JSON.parse(
    fs.readFileSync(path.join(BUS_MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  ) as { servos: Record<string, unknown>[]; poses: Record<string, unknown> };
  raw.servos[4] = { ...raw.servos[4], units: 'angle', polarity, min: -limit, max: limit };
  raw.servos = raw.servos.slice(0, servos);
  if (servos < 6)
    raw.poses = {
      home: { unit: 'servo', servos: { '000': 0, '001': 0, '002': 0, '003': 0, '004': 0 } },
    };
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  return parsed.profile;
}

test('a polarity flip reads and moves the servo the other way, without moving it', () => {
  const clock = new FakeClock();
  const bus = createEmulatedBus({
    protocol: 'dynamixel',
    startMs: clock.now(),
    servos: [0, 1, 2, 3, 4, 5].map((id) => ({ id })),
  });
  let wrist = NaN;
  const reader = createReader({
    onGroup: (g) => {
      for (const f of g.frames) if (f.type === 'angle' && f.id === 4) wrist = f.deg;
    },
  });
  const core: BusGatewayCore = new BusGatewayCore(
    { armId: 'a1', protocol: 'dynamixel', profile: profile(1) },
    {
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (h) => clock.clearTimeout(h),
      onFirst: () => {},
      publish: (topic, payload) => topic.endsWith('/status') && reader.feed(payload),
      write: (data) => {
        bus.advance(clock.now());
        const reply = bus.feed(data);
        if (reply.length) core.fromSerial(reply);
        return true;
      },
    },
  );
  core.brokerConnected(true);
  core.serialOpened();
  clock.advance(100);
  const servo = bus.servo(4)!;
  core.fromControl('#004A+030.00T0000!');
  clock.advance(2000);
  expect(servo.position).toBe(2048 + 341);
  expect(wrist).toBe(30);

  expect(core.reconfigure(profile(-1))).toBe('');
  clock.advance(200);
  expect(wrist).toBeCloseTo(-30, 1);
  expect(servo.position).toBe(2048 + 341);
  expect(servo.torque).toBe(true);

  core.fromControl('#004A+010.00T0000!');
  clock.advance(2000);
  expect(servo.position).toBe(2048 - 114);
  expect(wrist).toBe(10);

  expect(core.reconfigure(profile(1, 5))).toMatch(/drives servos .*: restart the gateway/);
  expect(core.reconfigure(profile(1, 6, 360))).toMatch(/servos 004 would switch multi-turn/);
  core.fromControl('#004A+020.00T0000!');
  clock.advance(2000);
  expect(servo.position).toBe(2048 - 228);
});
