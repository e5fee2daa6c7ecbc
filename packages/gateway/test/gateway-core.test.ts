import { describe, expect, test } from 'vitest';
import { OPERATOR_BEAT_MS, OPERATOR_LEASE_MS } from '@armtwin/protocol';
import { GatewayCore } from '../src/gateway.ts';
import { FakeClock } from '@armtwin/protocol/fake-clock';

function harness() {
  const clock = new FakeClock();
  const published: { topic: string; payload: string; retain: boolean }[] = [];
  const written: string[] = [];
  let lineUp = true;
  const core = new GatewayCore('arm1', {
    publish: (topic, payload, opts) =>
      published.push({ topic, payload: payload.toString(), retain: opts.retain }),
    write: (data) => (lineUp ? (written.push(data.toString()), true) : false),
    now: () => 1_700_000_000_000,
    setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
    clearTimeout: (h) => clock.clearTimeout(h),
    onFirst: () => {},
  });
  return { core, clock, published, written, setLine: (up: boolean) => (lineUp = up) };
}

describe('GatewayCore', () => {
  test('one stamped payload per serial chunk; frames split across chunks; groups kept; device $TIM dropped', () => {
    const { core, published } = harness();
    core.fromSerial(Buffer.from('{#000P1500!#001P16'));
    expect(published).toEqual([]);
    core.fromSerial(Buffer.from('12!}#001T045V7400!$TIM:5!$PNG:3!xx'));
    core.fromSerial(Buffer.from('{#000P1500!#00XP1!}'));
    expect(published.map((p) => p.payload)).toEqual([
      '$TIM:1700000000000!{#000P1500!#001P1612!}#001T045V7400!$PNG:3!',
      '$TIM:1700000000000!{#000P1500!}',
    ]);
    expect(published.every((p) => p.topic === 'arm/arm1/status' && !p.retain)).toBe(true);
    expect(core.counters.rejected).toEqual({ junk: 1, malformed: 1 });
  });

  test('control goes to the line verbatim; refused with $ERR while the line is down', () => {
    const { core, published, written, setLine } = harness();
    core.fromControl(Buffer.from('#000P1500T1000!$PNG:1!'));
    expect(written).toEqual(['#000P1500T1000!$PNG:1!']);
    setLine(false);
    core.fromControl(Buffer.from('$PNG:2!'));
    expect(published.at(-1)?.payload).toBe('$TIM:1700000000000!$ERR:gateway: serial line down!');
  });

  test('presence: 1 only while the line is open and the broker connected', () => {
    const { core, published } = harness();
    const online = () =>
      published.filter((p) => p.topic === 'arm/arm1/online').map((p) => p.payload);
    core.serialOpened();
    expect(online()).toEqual([]);
    core.brokerConnected(true);
    core.serialClosed();
    core.serialOpened();
    expect(online()).toEqual(['1', '0', '1']);
  });
});

describe('GatewayCore deadman', () => {
  test('operator presence 0 writes #255PDST! to the controller; 1 writes nothing', () => {
    const { core, written } = harness();
    core.fromOperator(Buffer.from('1'));
    core.fromOperator(Buffer.from('0'));
    expect(written).toEqual(['#255PDST!']);
    expect(core.counters.deadmanStops).toBe(1);
  });

  test('an operator that beats and falls silent: #255PDST! one lease after its last 1', () => {
    const { core, clock, written } = harness();
    for (let i = 0; i < 10; i++) {
      core.fromOperator(Buffer.from('1'));
      clock.advance(OPERATOR_BEAT_MS);
    }
    expect(written).toEqual([]);
    clock.advance(OPERATOR_LEASE_MS - OPERATOR_BEAT_MS - 1);
    expect(written).toEqual([]);
    clock.advance(1);
    expect(written).toEqual(['#255PDST!']);
    expect(core.counters.deadmanStops).toBe(1);
    clock.advance(60_000);
    expect(written).toEqual(['#255PDST!']);
  });

  test('a single 1 (a script holding the topic) is never timed out', () => {
    const { core, clock, written } = harness();
    core.fromOperator(Buffer.from('1'));
    clock.advance(60_000);
    expect(written).toEqual([]);
  });
});
