import { describe, expect, test } from 'vitest';
import {
  createReader,
  encodeGroup,
  encodeHealth,
  encodePosition,
  encodeTime,
  type Group,
} from '@armtwin/protocol';
import { SimRunner, type PayloadKind } from '../src/runner.ts';
import { StatusWriter } from '../src/status-writer.ts';
import { TickLoop } from '../src/tick-loop.ts';
import { parseFaults } from '../src/faults.ts';
import { FakeClock } from '@armtwin/protocol/fake-clock';

function harness(options: ConstructorParameters<typeof SimRunner>[2] = {}) {
  const clock = new FakeClock();
  const sent: { text: string; kind: PayloadKind; at: number; samples: number }[] = [];
  const runner = new SimRunner(
    {
      send: (p, kind, n) =>
        sent.push({ text: p.toString('latin1'), kind, at: clock.now(), samples: n }),
    },
    clock,
    options,
  );
  return { clock, sent, runner };
}

/** Every state sample: [$TIM, pwm of servo i]. */
function samples(payloads: string[], servo = 0): [number, number][] {
  const out: [number, number][] = [];
  const reader = createReader({
    onGroup: (g: Group) => {
      const f = g.frames[servo];
      if (f?.type === 'position') out.push([g.time ?? NaN, f.pwm]);
    },
  });
  for (const p of payloads) reader.feed(p);
  return out;
}

describe('StatusWriter', () => {
  test('writes what the protocol encoders write', () => {
    const w = new StatusWriter(8);
    w.time(1_700_000_000_123)
      .groupStart()
      .position(0, 500)
      .position(254, 2500)
      .groupEnd()
      .health(1, 7, 812);
    expect(w.take().toString()).toBe(
      encodeTime(1_700_000_000_123) +
        encodeGroup([encodePosition(0, 500), encodePosition(254, 2500)]) +
        encodeHealth(1, 7, 812),
    );
  });
});

describe('TickLoop', () => {
  test('does not drift, and batches the ticks of a late wake-up', () => {
    const clock = new FakeClock(0);
    const seen: number[] = [];
    const loop = new TickLoop(clock, (t, n) => seen.push(...Array.from(t.subarray(0, n))), {
      hz: 1000,
    });
    loop.startLoop();
    clock.advance(1000.5, 0.5); // every wake-up 0.5 ms late
    expect(seen).toHaveLength(1000);
    expect(seen[999]).toBe(1000);
    expect(new Set(seen).size).toBe(1000);
    clock.advance(15, 5); // very late wake-ups: batches
    expect(seen.filter((t) => t <= 1010)).toHaveLength(1010);
    expect(loop.batches).toBeGreaterThan(0);
  });
});

describe('SimRunner', () => {
  test('streams stamped state at the rate with unique stamps, and health at its rate', () => {
    const { clock, sent, runner } = harness({ rate: 250 });
    runner.start();
    clock.advance(1003, 3);
    const state = sent.filter((s) => s.kind === 'state').map((s) => s.text);
    const stamps = samples(state).map(([t]) => t);
    expect(stamps).toHaveLength(250);
    expect(new Set(stamps).size).toBe(250);
    expect(stamps[1]! - stamps[0]!).toBe(4);
    expect(sent.filter((s) => s.kind === 'health')).toHaveLength(2);
    expect(sent.find((s) => s.kind === 'health')!.text).toMatch(
      /^\$TIM:\d+!\{(#00\dT\d{3}V\d{4}!){6}\}$/,
    );
  });

  test('each payload says how many samples it carries: several after a late wake-up', () => {
    const { clock, sent, runner } = harness({ rate: 250 });
    runner.start();
    clock.advance(1000, 15); // every wake-up 15 ms late: payloads of several samples
    const state = sent.filter((s) => s.kind === 'state');
    const told = state.reduce((n, s) => n + s.samples, 0);
    expect(told).toBe(samples(state.map((s) => s.text)).length);
    expect(told).toBe(runner.counters.stateSamples);
    expect(Math.max(...state.map((s) => s.samples))).toBeGreaterThan(1);
    expect(sent.filter((s) => s.kind === 'health').every((s) => s.samples === 1)).toBe(true);
  });

  test('replies to one chunk leave in one stamped payload; junk gets $ERR and the sim goes on', () => {
    const { clock, sent, runner } = harness();
    runner.start();
    runner.receive('$PNG:1!garbage#000PRAD!');
    runner.receive('$PNG:2!');
    const replies = sent.filter((s) => s.kind === 'reply').map((s) => s.text);
    expect(replies).toEqual([
      `$TIM:${clock.now()}!$PNG:1!$ERR:junk garbage!#000P1500!`,
      `$TIM:${clock.now()}!$PNG:2!`,
    ]);
  });

  test('a move measured from the stream arrives at the commanded time', () => {
    const { clock, sent, runner } = harness({ rate: 100 });
    runner.start();
    clock.advance(95);
    const t0 = clock.now();
    runner.receive('#000P1800T0500!');
    clock.advance(1000);
    const arrived = samples(sent.filter((s) => s.kind === 'state').map((s) => s.text)).find(
      ([, p]) => p === 1800,
    );
    expect(arrived![0] - t0).toBeGreaterThanOrEqual(500);
    expect(arrived![0] - t0).toBeLessThanOrEqual(510);
  });

  test('drop and latency faults; #255PDST! bypasses latency and discards queued commands', () => {
    const { clock, sent, runner } = harness({ rate: 100, random: () => 0.5 });
    runner.start();
    runner.applyFaults(parseFaults('[{"fault":"drop","percent":60},{"fault":"latency","ms":200}]'));
    clock.advance(1000);
    expect(sent.filter((s) => s.kind === 'state')).toHaveLength(0);
    runner.applyFaults(parseFaults('{"fault":"drop","percent":0}'));
    runner.receive('#000P2000T1000!');
    clock.advance(100);
    runner.receive('#255PDST!');
    clock.advance(1000);
    expect(runner.model.pwmAt(0, clock.now())).toBe(1500);
    expect(runner.counters.discardedQueued).toBe(1);
    const first = sent.find((s) => s.kind === 'state')!;
    expect(first.at - Number(/\$TIM:(\d+)/.exec(first.text)![1])).toBe(200);
  });

  test('stall freezes a servo and heats it; overheat passes 60 and 75 °C; undervolt sags the supply', () => {
    const { clock, runner } = harness();
    runner.start();
    runner.applyFaults(
      parseFaults(
        '[{"fault":"stall","id":1},{"fault":"overheat","id":2},{"fault":"undervolt","mv":6300}]',
      ),
    );
    runner.receive('#001P2000T0500!');
    clock.advance(60_000);
    const s = runner.model.servos;
    expect(runner.model.pwmAt(1, clock.now())).toBe(1500);
    expect(s.temp[1]!).toBeGreaterThan(75);
    expect(s.temp[2]!).toBeGreaterThan(80);
    expect(s.mv[0]!).toBeLessThan(6500);
    runner.applyFaults(parseFaults('{"fault":"clear"}'));
    clock.advance(1000);
    expect(runner.model.pwmAt(1, clock.now())).toBe(2000);
    expect(runner.faults).toEqual({
      stalled: [],
      overheated: {},
      undervoltMv: 0,
      dropPercent: 0,
      latencyMs: 0,
    });
    expect(() => parseFaults('{"fault":"melt"}')).toThrow(/bad fault/);
  });
});
