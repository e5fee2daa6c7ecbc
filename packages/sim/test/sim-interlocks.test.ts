/**
 * The controller's interlocks: the command rate limit, the deadman, the emergency
 * stop over queued commands under the latency fault, the joint limits, the payload bound.
 * Fake clock; the runner is fed bytes as the MQTT or serial side would.
 */
import { describe, expect, test } from 'vitest';
import { TokenBucket } from '@armtwin/controller';
import { SimRunner, type PayloadKind } from '../src/runner.ts';
import { parseFaults } from '../src/faults.ts';
import { FakeClock } from '@armtwin/protocol/fake-clock';

function harness(options: ConstructorParameters<typeof SimRunner>[2] = {}) {
  const clock = new FakeClock();
  const sent: { text: string; kind: PayloadKind }[] = [];
  const runner = new SimRunner(
    { send: (p, kind) => sent.push({ text: p.toString('latin1'), kind }) },
    clock,
    options,
  );
  const replies = () =>
    sent.filter((s) => s.kind === 'reply').map((s) => s.text.replace(/^\$TIM:\d+!/, ''));
  return { clock, sent, runner, replies, pwm: (i: number) => runner.model.pwmAt(i, clock.now()) };
}

describe('TokenBucket', () => {
  test('gives the burst at once, then the rate', () => {
    const b = new TokenBucket(50, 100, 0);
    let n = 0;
    while (b.take(0)) n++;
    expect(n).toBe(100);
    expect(b.take(19)).toBe(false); // 0.95 token
    expect(b.take(20)).toBe(true); // 1 token after 20 ms at 50/s
    expect(b.take(20)).toBe(false);
  });
});

describe('rate limit (50 commands/s, burst 100)', () => {
  test('over the burst: dropped, never queued, one $ERR:rate limit! per run', () => {
    const { clock, runner, replies } = harness();
    for (let i = 0; i < 150; i++) runner.receive('#000PRAD!');
    const r = replies();
    expect(r.filter((x) => x.startsWith('#000P'))).toHaveLength(100);
    expect(r.filter((x) => x === '$ERR:rate limit!')).toHaveLength(1);
    expect(runner.counters.rateLimited).toBe(50);
    clock.advance(1000); // 50 tokens back; nothing dropped comes back with them
    runner.receive('#000PRAD!');
    expect(replies().at(-1)).toMatch(/^#000P\d{4}!$/);
    expect(replies().filter((x) => x.startsWith('#000P'))).toHaveLength(101);
  });

  test('pings are never limited: they move nothing and measure the link', () => {
    const { runner, replies } = harness();
    for (let i = 0; i < 1000; i++) runner.receive(`$PNG:${i}!`);
    expect(replies().filter((x) => x.startsWith('$PNG:'))).toHaveLength(1000);
    expect(runner.counters.rateLimited).toBe(0);
  });

  test('a {…} group is one command; stops and #255PDST! are never limited', () => {
    const { runner, replies, pwm, clock } = harness();
    for (let i = 0; i < 100; i++) runner.receive('{#000PRAD!#001PRAD!}');
    runner.receive('#000P2000T1000!');
    expect(replies().at(-1)).toBe('$ERR:rate limit!');
    expect(pwm(0)).toBe(1500); // the move was dropped
    runner.receive('#001PDST!');
    runner.receive('{#255PDST!}');
    runner.receive('#255PDST!');
    expect(runner.model.counters.stops).toBe(1);
    expect(runner.model.counters.emergencyStops).toBe(2);
    expect(runner.counters.rateLimited).toBe(1);
    clock.advance(1);
  });

  test('malformed input costs no token: a ping in a flood of junk is answered', () => {
    const { runner, replies } = harness();
    for (let i = 0; i < 1000; i++) runner.receive('#000P9999!'.repeat(100));
    runner.receive('$PNG:7!');
    expect(replies().at(-1)).toBe('$PNG:7!');
    expect(runner.counters.rejected['out-of-range']).toBe(100_000);
    expect(runner.counters.rateLimited).toBe(0);
  });
});

describe('deadman (operator presence goes to 0)', () => {
  test('while a move runs: every servo stops where it is, answered $ERR:deadman stop!', () => {
    const { clock, runner, replies, pwm } = harness();
    runner.start();
    runner.receive('{#000P2500T2000!#002P1000T2000!}');
    clock.advance(500);
    expect(runner.operatorLeft()).toBe(true);
    const [p0, p2] = [pwm(0), pwm(2)];
    expect(p0).toBeGreaterThan(1500);
    expect(p0).toBeLessThan(2500);
    clock.advance(3000);
    expect([pwm(0), pwm(2)]).toEqual([p0, p2]);
    expect(replies().at(-1)).toBe('$ERR:deadman stop!');
    expect(runner.counters.deadmanStops).toBe(1);
    expect(runner.model.counters.emergencyStops).toBe(1);
    runner.stop();
  });

  test('at rest it does nothing (a retained 0 at start-up is no event)', () => {
    const { runner, replies } = harness();
    expect(runner.operatorLeft()).toBe(false);
    expect(replies()).toEqual([]);
    expect(runner.model.counters.emergencyStops).toBe(0);
  });

  test('with commands still held by the latency fault: they are discarded', () => {
    const { clock, runner, pwm } = harness();
    runner.applyFaults(parseFaults('{"fault":"latency","ms":300}'));
    runner.receive('#000P2000T0100!');
    clock.advance(100);
    expect(runner.operatorLeft()).toBe(true);
    clock.advance(2000);
    expect(pwm(0)).toBe(1500);
    expect(runner.counters.discardedQueued).toBe(1);
  });
});

describe('emergency stop overrides everything queued', () => {
  test('latency fault + queued moves: #255PDST! acts on arrival, none of them ever runs', () => {
    const { clock, runner, pwm, replies } = harness();
    runner.start();
    runner.receive('#000P1600T0000!');
    clock.advance(300);
    expect(pwm(0)).toBe(1600);
    runner.applyFaults(parseFaults('{"fault":"latency","ms":500}'));
    runner.receive('#000P2400T0200!');
    clock.advance(100);
    runner.receive('{#001P1000T0200!#002P1000T0200!}');
    clock.advance(100);
    runner.receive('$KMS:150,0,200,500!');
    clock.advance(100);
    runner.receive('#255PDST!$PNG:5!'); // the ping after the stop is still delayed
    clock.advance(5000);
    expect([pwm(0), pwm(1), pwm(2), pwm(3)]).toEqual([1600, 1500, 1500, 1500]);
    expect(runner.counters.discardedQueued).toBe(3);
    expect(runner.model.counters.emergencyStops).toBe(1);
    expect(replies().some((r) => r.startsWith('$KMS:'))).toBe(false);
    expect(replies().at(-1)).toBe('$PNG:5!');
    runner.stop();
  });
});

describe('limits are checked by the controller again', () => {
  test('a move or a group outside a joint limit is refused and nothing moves', () => {
    const { clock, runner, pwm, replies } = harness();
    runner.receive('#001P2400T0100!');
    runner.receive('{#000P2000T0100!#005P1000T0100!}');
    runner.receive('#255P2400T0100!');
    clock.advance(500);
    expect(replies()).toEqual([
      '$ERR:limit 001 P2400 outside 833-2167!',
      '$ERR:group rejected: limit 005 P1000 outside 1500-2167!',
      '$ERR:limit 001 P2400 outside 833-2167!',
    ]);
    expect([0, 1, 2, 3, 4, 5].map(pwm)).toEqual([1500, 1500, 1500, 1500, 1500, 1500]);
    expect(runner.model.counters.rejected.limit).toBe(3);
  });

  test('$KMS to a point outside the reach is refused with its code; nothing moves', () => {
    const { clock, runner, pwm, replies } = harness();
    runner.receive('$KMS:1000,0,100,500!');
    clock.advance(600);
    expect(replies()).toEqual(['$KMS:2!']);
    expect(pwm(0)).toBe(1500);
  });
});

describe('payload bound', () => {
  test('a control payload over 64 KiB is refused whole and counted', () => {
    const { clock, runner, pwm, replies } = harness();
    runner.receive('#000P2000T0000!' + ' '.repeat(70_000));
    clock.advance(100);
    expect(replies()).toEqual(['$ERR:payload too large!']);
    expect(pwm(0)).toBe(1500);
    expect(runner.counters.oversizePayloads).toBe(1);
  });
});
