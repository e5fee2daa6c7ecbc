import { describe, expect, test } from 'vitest';
import { GatewayCore } from '../src/gateway/gateway.ts';

function harness() {
  const published: { topic: string; payload: string; retain: boolean }[] = [];
  const written: string[] = [];
  let lineUp = true;
  const core = new GatewayCore('arm1', {
    publish: (topic, payload, opts) =>
      published.push({ topic, payload: payload.toString(), retain: opts.retain }),
    write: (data) => (lineUp ? (written.push(data.toString()), true) : false),
    now: () => 1_700_000_000_000,
    onFirst: () => {},
  });
  return { core, published, written, setLine: (up: boolean) => (lineUp = up) };
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
});
