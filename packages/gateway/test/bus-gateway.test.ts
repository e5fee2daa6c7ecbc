/**
 * The bus gateway's core with an emulated servo bus as its wire (no serial port, no broker):
 * the bytes the core writes go to `createEmulatedBus`, its answers come straight back, time is
 * a manual clock. Both buses: start-up (ping, torque, multi-turn), angle and health frames,
 * moves with their limits and speeds, stop and deadman holding position, missing servos,
 * torque off on request, the line going away and coming back.
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { parseProfile, type Profile } from '@armtwin/robot';
import { createMotionRobot, exactPwmFromServo, tipPose } from '@armtwin/motion';
import { createReader, type Frame } from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import {
  createEmulatedBus,
  degreesToTicks,
  type BusProtocol,
  type EmulatedBus,
} from '@armtwin/servo-bus';
import { floorKeepOut, numericKms } from '@armtwin/controller';
import { BusGatewayCore, BUS_MODELS_DIR, LOST_AFTER_MS } from '../src/index.ts';

/** armtwin5 with its wrist roll (004) able to turn ±360°. */
function profile(): Profile {
  const raw = JSON.parse(
    fs.readFileSync(path.join(BUS_MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  ) as { servos: Record<string, unknown>[] };
  raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  return parsed.profile;
}

function rig(protocol: BusProtocol, ids = [0, 1, 2, 3, 4, 5]) {
  const clock = new FakeClock();
  const bus: EmulatedBus = createEmulatedBus({
    protocol,
    startMs: clock.now(),
    servos: ids.map((id) => ({ id })),
  });
  const items: { frame?: Frame; group?: Frame[] }[] = [];
  const retained = new Map<string, string>();
  const reader = createReader({
    onFrame: (frame) => frame.type !== 'time' && items.push({ frame }),
    onGroup: (g) => items.push({ group: g.frames }),
  });
  let open = true;
  /** The servos answer nothing (a stall, or the bus unplugged with the port still open). */
  let muted = false;
  /** Answers arrive this late (ms); 0 = at once. */
  let lateMs = 0;
  const core: BusGatewayCore = new BusGatewayCore(
    {
      armId: 'a1',
      protocol,
      profile: profile(),
      kms: numericKms(createMotionRobot(profile())),
      keepOut: floorKeepOut(createMotionRobot(profile())),
    },
    {
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (h) => clock.clearTimeout(h),
      onFirst: () => {},
      publish: (topic, payload) => {
        if (topic.endsWith('/status')) reader.feed(payload);
        else retained.set(topic, payload);
      },
      write: (data) => {
        if (!open) return false;
        bus.advance(clock.now());
        const reply = bus.feed(data);
        if (reply.length === 0 || muted) return true;
        if (lateMs > 0) clock.setTimeout(() => core.fromSerial(reply), lateMs);
        else core.fromSerial(reply);
        return true;
      },
    },
  );
  core.brokerConnected(true);
  core.serialOpened();
  clock.advance(100);
  /** Latest angle reported for servo `id`. */
  const angle = (id: number): number | undefined => {
    for (let i = items.length - 1; i >= 0; i--) {
      const f = items[i]!.group?.find((x) => x.type === 'angle' && x.id === id);
      if (f?.type === 'angle') return f.deg;
    }
    return undefined;
  };
  const errors = () =>
    items.flatMap((i) => (i.frame?.type === 'controllerError' ? [i.frame.text] : []));
  const setOpen = (value: boolean) => {
    open = value;
    if (value) core.serialOpened();
    else core.serialClosed();
  };
  const setLate = (ms: number) => (lateMs = ms);
  const setMuted = (value: boolean) => (muted = value);
  return { clock, bus, core, items, retained, angle, errors, setOpen, setLate, setMuted };
}

describe.each(['dynamixel', 'feetech'] as const)('bus gateway core on %s', (protocol) => {
  test('sets the servos up, then streams angle groups at the state rate and health at 2 Hz', () => {
    const r = rig(protocol);
    expect(r.retained.get('arm/a1/online')).toBe('1');
    expect(r.core.found.size).toBe(6);
    expect(r.bus.servos.every((s) => s.torque)).toBe(true);
    const before = r.items.length;
    r.clock.advance(1000);
    const groups = r.items.slice(before).flatMap((i) => (i.group ? [i.group] : []));
    const states = groups.filter((g) => g[0]?.type === 'angle');
    const health = groups.filter((g) => g[0]?.type === 'health');
    expect(states.length).toBeGreaterThanOrEqual(45);
    expect(states.length).toBeLessThanOrEqual(51);
    expect(health.length).toBe(2);
    expect(states.at(-1)).toHaveLength(6);
    expect(r.angle(0)).toBe(0);
    const h = health[0]!.find((f) => f.type === 'health' && f.id === 1);
    expect(h).toMatchObject({ type: 'health', temp: 25 });
  });

  test('a timed angle move arrives on time; a pulse move goes through the profile', () => {
    const r = rig(protocol);
    r.core.fromControl('#001A+045.00T1000!');
    r.clock.advance(500);
    const half = r.angle(1)!;
    expect(half).toBeGreaterThan(15);
    expect(half).toBeLessThan(35);
    r.clock.advance(700);
    expect(Math.abs(r.angle(1)! - 45)).toBeLessThan(0.1);
    r.core.fromControl('#002P0500T0000!'); // −135° at the profile's top speed (+135° would put the hand under the floor)
    r.clock.advance(1000);
    expect(Math.abs(r.angle(2)! + 135)).toBeLessThan(0.1);
  });

  test('a ±360° joint goes multi-turn and +350.00° comes back as +350.00', () => {
    const r = rig(protocol);
    r.core.fromControl('#004A+350.00T0500!');
    r.clock.advance(2000);
    expect(r.angle(4)).toBe(350);
    expect(r.bus.servo(4)!.position).toBe(degreesToTicks(350, { id: 4 }));
  });

  test('moves beyond the limits are refused with $ERR, a group all or nothing', () => {
    const r = rig(protocol);
    r.core.fromControl('#004A+361.00T0100!');
    r.core.fromControl('{#000A+010.00T0100!#001A+095.00T0100!}');
    r.clock.advance(500);
    expect(r.errors()).toEqual([
      'limit 004 A361 outside -360..360',
      'group rejected: limit 001 A95 outside -90..90', // a refused group is worded as on the sim (one controller)
    ]);
    expect(r.angle(0)).toBe(0); // the group's valid move was not made either
  });

  test('#255PDST! holds the arm short of a slow move, beating queued goals', () => {
    const r = rig(protocol);
    r.core.fromControl('#000A+090.00T9000!');
    r.clock.advance(1000);
    r.core.fromControl('#255PDST!');
    r.clock.advance(2000);
    const held = r.angle(0)!;
    expect(held).toBeGreaterThan(5);
    expect(held).toBeLessThan(20);
    r.clock.advance(1000);
    expect(r.angle(0)).toBe(held);
  });

  test('#255PDST! holds the arm even when the read of where it is gets no answer', () => {
    const r = rig(protocol);
    r.core.fromControl('#000A+090.00T9000!');
    r.clock.advance(1000);
    r.setMuted(true); // the stop's read of the present positions is missed
    r.core.fromControl('#255PDST!');
    r.clock.advance(300);
    r.setMuted(false);
    r.clock.advance(2000);
    const held = r.angle(0)!;
    expect(held).toBeGreaterThan(5);
    expect(held).toBeLessThan(20);
  });

  test('the deadman holds position when a beating operator falls silent', () => {
    const r = rig(protocol);
    r.core.fromOperator('1');
    r.core.fromOperator('1');
    r.core.fromControl('#000A+090.00T9000!');
    r.clock.advance(3000); // the 2.5 s lease lapses during the move
    const held = r.angle(0)!;
    expect(held).toBeLessThan(30);
    r.clock.advance(1000);
    expect(r.angle(0)).toBe(held);
    expect(r.core.counters.deadmanStops).toBe(1);
  });

  test('$KMS goes through the IK: $KMS:0! and the tip gets there; unreachable is $KMS:2!', () => {
    const r = rig(protocol);
    r.core.fromControl('$KMS:150,50,120,800!');
    expect(r.items.at(-1)?.frame).toMatchObject({ type: 'kmsResult', code: 0 });
    r.clock.advance(1500);
    const robot = createMotionRobot(profile());
    const pwm = robot.profile.servos.map((s, i) => exactPwmFromServo(s, r.angle(i)!));
    const tip = tipPose(robot, pwm);
    expect(Math.hypot(tip.x - 150, tip.y - 50, tip.z - 120)).toBeLessThan(1);
    r.core.fromControl('$KMS:1000,0,100,500!');
    expect(r.items.at(-1)?.frame).toMatchObject({ type: 'kmsResult', code: 2 });
  });

  test('goals that would put the hand below the floor are refused ($ERR, $KMS:1!), counted', () => {
    const r = rig(protocol);
    r.core.fromControl('#001A-090.00T0200!'); // upper arm and forearm level: tip at z 100
    r.clock.advance(1000);
    expect(r.angle(1)).toBeCloseTo(-90, 1);
    r.core.fromControl('#002A-090.00T0200!'); // forearm down: tip at z −148
    r.core.fromControl('$KMS:200,0,-50,800!'); // reachable, but under the floor
    expect(r.items.at(-1)?.frame).toMatchObject({ type: 'kmsResult', code: 1 });
    r.clock.advance(1000);
    expect(r.errors()).toEqual([expect.stringMatching(/^floor: tip 148\.0 mm below the floor/)]);
    expect(r.angle(2)).toBe(0);
    expect(r.core.controller.counters.rejected.floor).toBe(2);
  });

  test('answers arriving after their time-out are drained, never taken for the next ones', () => {
    const r = rig(protocol);
    r.core.fromControl('#001A+030.00T0000!#003A-020.00T0000!');
    r.clock.advance(500);
    r.setLate(45); // just past the 40 ms margin
    r.clock.advance(150);
    r.setLate(0);
    const from = r.items.length;
    r.clock.advance(1000);
    const groups = r.items.slice(from).flatMap((i) => (i.group ? [i.group] : []));
    expect(groups.length).toBeGreaterThan(40);
    for (const g of groups)
      for (const f of g) {
        if (f.type === 'angle') expect(f.deg).toBe(f.id === 1 ? 30 : f.id === 3 ? -20 : 0);
        if (f.type === 'health') expect(f.temp).toBe(25);
      }
    expect(r.core.lineCounters.timeouts).toBeGreaterThan(0);
    expect(r.core.found.size).toBe(6);
  });

  test('$PNG, PRAD and PRTV are answered', () => {
    const r = rig(protocol);
    r.core.fromControl('$PNG:7!#003PRAD!#003PRTV!');
    const replies = r.items.slice(-3).map((i) => i.frame);
    expect(replies).toMatchObject([
      { type: 'ping', seq: 7 },
      { type: 'angle', id: 3, deg: 0 },
      { type: 'health', id: 3, temp: 25, mv: protocol === 'dynamixel' ? 12000 : 7400 },
    ]);
  });

  test('missing servos are reported and left out of the reads', () => {
    const r = rig(protocol, [0, 1, 2, 3, 4]);
    expect(r.errors()).toContain('missing servos 005');
    expect(r.core.found.has(5)).toBe(false);
    expect(r.items.at(-1)?.group).toHaveLength(5);
  });

  test('reads missed for a moment (a stall) lose no servo; no answer for a second does', () => {
    const r = rig(protocol);
    const missing = () => r.errors().filter((e) => e.startsWith('missing servos'));
    const timeouts = r.core.lineCounters.timeouts;
    r.setMuted(true);
    r.clock.advance(500);
    r.setMuted(false);
    expect(r.core.lineCounters.timeouts - timeouts).toBeGreaterThanOrEqual(3);
    r.clock.advance(500);
    expect(missing()).toEqual([]);
    expect(r.core.found.size).toBe(6);
    r.setMuted(true); // unplugged
    r.clock.advance(LOST_AFTER_MS - 100);
    expect(missing()).toEqual([]);
    r.clock.advance(400);
    expect(missing()).toEqual(['missing servos 000 001 002 003 004 005']);
    expect(r.core.found.size).toBe(0);
  });

  test('torque on after a missed read holds where the servo was, not at a goal sent while limp', () => {
    const r = rig(protocol);
    r.core.fromTorque('0');
    r.clock.advance(100);
    r.core.fromControl('#002A-030.00T0500!'); // written to the limp servo: it does not move
    r.clock.advance(700);
    const at = r.angle(2)!;
    expect(at).toBeCloseTo(0, 0);
    r.setMuted(true); // the hold's read of the present positions gets no answer
    r.core.fromTorque('1');
    r.clock.advance(300);
    r.setMuted(false);
    r.clock.advance(1000);
    expect(r.bus.servos.every((s) => s.torque)).toBe(true);
    expect(r.angle(2)).toBeCloseTo(at, 0);
  });

  test('torque off and on by request; the line going and coming back', () => {
    const r = rig(protocol);
    r.core.fromTorque('0');
    r.clock.advance(50);
    expect(r.bus.servos.some((s) => s.torque)).toBe(false);
    r.bus.servo(3)!.setPosition(degreesToTicks(20, { id: 3 })); // moved by hand
    r.core.fromTorque('1');
    r.clock.advance(200);
    expect(r.bus.servos.every((s) => s.torque)).toBe(true);
    expect(Math.round(r.angle(3)!)).toBe(20); // held where the hand left it
    r.setOpen(false);
    expect(r.retained.get('arm/a1/online')).toBe('0');
    r.core.fromControl('#000A+010.00T0100!');
    expect(r.errors().at(-1)).toBe('gateway: serial line down');
    r.setOpen(true);
    r.clock.advance(200);
    expect(r.retained.get('arm/a1/online')).toBe('1');
    r.core.fromControl('#000A+010.00T0100!');
    r.clock.advance(300);
    expect(r.angle(0)).toBe(10);
  });
});
