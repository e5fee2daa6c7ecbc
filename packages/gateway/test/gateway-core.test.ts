/**
 * The LSC gateway's core (no serial port, no broker): what reaches the board's firmware and
 * what is answered on status. Every command passes the controller core first (limits, zones,
 * `$KMS` through the profile's IK, the rate limit, the e-stop), as on the simulator and the bus;
 * what passes is written as frames the firmware executes itself. The profile is armtwin5 with a
 * table-top keep-out zone; time is a fake clock.
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { numericKms, zonesKeepOut } from '@armtwin/controller';
import { createMotionRobot } from '@armtwin/motion';
import { OPERATOR_BEAT_MS, OPERATOR_LEASE_MS } from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { parseProfile } from '@armtwin/robot';
import { GatewayCore } from '../src/gateway.ts';
import { BUS_MODELS_DIR } from '../src/start-bus-gateway.ts';

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
const T0 = 1_700_000_000_000;
const AT_HOME = `{${[0, 1, 2, 3, 4, 5].map((i) => `#00${i}P1500!`).join('')}}`;

function harness() {
  const raw = JSON.parse(
    fs.readFileSync(path.join(BUS_MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  ) as Record<string, unknown>;
  const parsed = parseProfile({ ...raw, keepOut: { zones: [TABLE] } });
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  const robot = createMotionRobot(parsed.profile);
  const clock = new FakeClock(T0);
  const published: { topic: string; payload: string; retain: boolean }[] = [];
  const written: string[] = [];
  let lineUp = true;
  const core = new GatewayCore(
    {
      armId: 'arm1',
      profile: parsed.profile,
      kms: numericKms(robot),
      keepOut: zonesKeepOut(robot),
    },
    {
      publish: (topic, payload, opts) =>
        published.push({ topic, payload: payload.toString(), retain: opts.retain }),
      write: (data) => (lineUp ? (written.push(data.toString()), true) : false),
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (h) => clock.clearTimeout(h),
      onFirst: () => {},
    },
  );
  core.brokerConnected(true);
  core.serialOpened();
  core.fromSerial(Buffer.from(AT_HOME)); // the board reports where it is
  published.length = 0;
  /** The status replies (payloads without the `$TIM` stamp). */
  const replies = () =>
    published.filter((p) => p.topic === 'arm/arm1/status').map((p) => p.payload.slice(19));
  const setLine = (up: boolean) => (lineUp = up);
  return { core, clock, published, written, replies, setLine };
}

describe('GatewayCore', () => {
  test('one stamped payload per serial chunk; frames split across chunks; groups kept; device $TIM dropped', () => {
    const { core, published } = harness();
    core.fromSerial(Buffer.from('{#000P1500!#001P16'));
    expect(published).toEqual([]);
    core.fromSerial(Buffer.from('12!}#001T045V7400!$TIM:5!$PNG:3!xx'));
    core.fromSerial(Buffer.from('{#000P1500!#00XP1!}'));
    expect(published.map((p) => p.payload)).toEqual([
      `$TIM:${T0}!{#000P1500!#001P1612!}#001T045V7400!$PNG:3!`,
      `$TIM:${T0}!{#000P1500!}`,
    ]);
    expect(published.every((p) => p.topic === 'arm/arm1/status' && !p.retain)).toBe(true);
    expect(core.counters.rejected).toEqual({ junk: 1, malformed: 1 });
  });

  test('what passes the controller reaches the board: timed moves, a group whole, reads and pings as they came', () => {
    const { core, written, replies } = harness();
    core.fromControl(
      Buffer.from('#000P1600T0200!{#001A+010.00T0500!#002P1400T0500!}$PNG:1!{#001PRAD!#002PRAD!}'),
    );
    expect(written).toEqual([
      '#000P1600T0200!',
      '{#001A+010.00T0500!#002P1400T0500!}',
      '$PNG:1!',
      '{#001PRAD!#002PRAD!}',
    ]);
    expect(replies()).toEqual([]);
  });

  test('refused before the board, answered as on the simulator: a limit, a servo it lacks, a group into a zone', () => {
    const { core, written, replies } = harness();
    core.fromControl(Buffer.from('#009P1500T1000!'));
    core.fromControl(Buffer.from('#005P1000T1000!'));
    core.fromControl(Buffer.from('{#001A-045.00T0500!#002A-045.00T0500!#003A-090.00T0500!}'));
    expect(written).toEqual([]);
    expect(replies()).toEqual([
      '$ERR:no servo 009!',
      '$ERR:limit 005 P1000 outside 1500-2166.6666666666665!',
      '$ERR:group rejected: zone: hand in "table"!',
    ]);
    expect(core.controller.counters.rejected).toMatchObject({
      'unknown-servo': 1,
      limit: 1,
      zone: 1,
    });
  });

  test('$KMS is solved by the controller: the pose goes to the board as one timed group; one into the table is answered 25', () => {
    const { core, written, replies } = harness();
    core.fromControl(Buffer.from('$KMS:150,0,200,1000!'));
    expect(replies()).toEqual(['$KMS:0!']);
    expect(written).toHaveLength(1);
    expect(written[0]).toMatch(/^\{(#00\dP\d{4}T1000!){3,}\}$/);
    core.fromControl(Buffer.from('$KMS:250,0,10,1000!'));
    expect(replies()[1]).toBe('$KMS:25!');
    expect(written).toHaveLength(1);
  });

  test('the rate limit drops a flood before the board; #255PDST! still goes through at once', () => {
    const { core, written, replies } = harness();
    const flood = Array.from({ length: 150 }, (_, k) => `#000P${1500 + (k % 50)}T0100!`).join('');
    core.fromControl(Buffer.from(flood + '#255PDST!'));
    expect(written).toHaveLength(101);
    expect(written.at(-1)).toBe('#255PDST!');
    expect(replies()).toEqual(['$ERR:rate limit!']);
  });

  test('while the line is down every command is answered $ERR:gateway: serial line down!', () => {
    const { core, replies, setLine } = harness();
    setLine(false);
    core.serialClosed();
    core.fromControl(Buffer.from('#000P1500T1000!'));
    core.fromControl(Buffer.from('$PNG:2!'));
    expect(replies()).toEqual([
      '$ERR:gateway: serial line down!',
      '$ERR:gateway: serial line down!',
    ]);
  });

  test('presence: 1 only while the line is open and the broker connected', () => {
    const { core, published } = harness();
    const online = () =>
      published.filter((p) => p.topic === 'arm/arm1/online').map((p) => p.payload);
    core.serialClosed();
    core.brokerConnected(false);
    core.serialOpened();
    expect(online()).toEqual(['0']);
    core.brokerConnected(true);
    core.serialClosed();
    core.serialOpened();
    expect(online()).toEqual(['0', '1', '0', '1']);
  });
});

describe('GatewayCore deadman', () => {
  test('the operator lets go while the arm moves: #255PDST! to the board, $ERR:deadman stop!; at rest nothing', () => {
    const { core, clock, written, replies } = harness();
    core.fromOperator(Buffer.from('1'));
    core.fromOperator(Buffer.from('0'));
    expect(written).toEqual([]);
    core.fromOperator(Buffer.from('1'));
    core.fromControl(Buffer.from('#000P2000T9000!'));
    clock.advance(1000);
    core.fromOperator(Buffer.from('0'));
    expect(written).toEqual(['#000P2000T9000!', '#255PDST!']);
    expect(replies()).toEqual(['$ERR:deadman stop!']);
    expect(core.counters.deadmanStops).toBe(1);
  });

  test('a beating operator falls silent mid-move: #255PDST! one lease after its last 1', () => {
    const { core, clock, written } = harness();
    core.fromControl(Buffer.from('#000P2000T9000!'));
    for (let i = 0; i < 10; i++) {
      core.fromOperator(Buffer.from('1'));
      clock.advance(OPERATOR_BEAT_MS);
    }
    clock.advance(OPERATOR_LEASE_MS - OPERATOR_BEAT_MS - 1);
    expect(written).toEqual(['#000P2000T9000!']);
    clock.advance(1);
    expect(written).toEqual(['#000P2000T9000!', '#255PDST!']);
    expect(core.counters.deadmanStops).toBe(1);
  });

  test('the board reporting a servo on its way counts as moving (a move it took from elsewhere)', () => {
    const { core, clock, written } = harness();
    core.fromOperator(Buffer.from('1'));
    core.fromSerial(Buffer.from('#000P1510!'));
    clock.advance(50);
    core.fromOperator(Buffer.from('0'));
    expect(written).toEqual(['#255PDST!']);
  });

  test('a single 1 (a script holding the topic) is never timed out', () => {
    const { core, clock, written } = harness();
    core.fromControl(Buffer.from('#000P2000T9000!'));
    core.fromOperator(Buffer.from('1'));
    clock.advance(60_000);
    expect(written).toEqual(['#000P2000T9000!']);
  });
});
