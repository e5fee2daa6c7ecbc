import { describe, expect, it } from 'vitest';
import { MoveCoalescer, type CoalescerClock } from '../src/core/link/MoveCoalescer.ts';

/** A hand-driven clock: `advance(ms)` runs the timers that fall due, in order. */
function fakeClock(): CoalescerClock & { advance(ms: number): void } {
  let now = 0;
  let timers: { at: number; fn: () => void; id: number }[] = [];
  let next = 1;
  return {
    now: () => now,
    setTimeout(fn, ms) {
      const id = next++;
      timers.push({ at: now + ms, fn, id });
      return id;
    },
    clearTimeout(id) {
      timers = timers.filter((t) => t.id !== id);
    },
    advance(ms) {
      const end = now + ms;
      for (;;) {
        timers.sort((a, b) => a.at - b.at);
        const t = timers[0];
        if (!t || t.at > end) break;
        timers.shift();
        now = t.at;
        t.fn();
      }
      now = end;
    },
  };
}

function setup() {
  const clock = fakeClock();
  const sent: { t: number; id: number; pwm: number }[] = [];
  const c = new MoveCoalescer(
    (id, pwm) => sent.push({ t: clock.now(), id, pwm }),
    { intervalMs: 50 },
    clock,
  );
  return { clock, sent, c };
}

describe('MoveCoalescer', () => {
  it('sends the first move at once', () => {
    const { sent, c } = setup();
    c.request(1, 1600);
    expect(sent).toEqual([{ t: 0, id: 1, pwm: 1600 }]);
  });

  it('sends at most 20 moves per second per servo while a slider is dragged, ending on the last value', () => {
    const { clock, sent, c } = setup();
    for (let ms = 0; ms < 1000; ms++) {
      c.request(0, 1000 + ms); // an input event every millisecond
      clock.advance(1);
    }
    clock.advance(100);
    expect(sent.length).toBeLessThanOrEqual(21);
    expect(sent.length).toBeGreaterThanOrEqual(19);
    for (let i = 1; i < sent.length; i++)
      expect(sent[i]!.t - sent[i - 1]!.t).toBeGreaterThanOrEqual(50);
    expect(sent.at(-1)!.pwm).toBe(1999);
  });

  it('coalesces each servo separately', () => {
    const { clock, sent, c } = setup();
    c.request(0, 1100);
    c.request(1, 1200);
    c.request(0, 1101);
    c.request(1, 1201);
    expect(sent.map((s) => s.pwm)).toEqual([1100, 1200]);
    clock.advance(50);
    expect(sent.map((s) => s.pwm)).toEqual([1100, 1200, 1101, 1201]);
  });

  it('drops pending moves on cancelAll (an emergency stop is not followed by a jog)', () => {
    const { clock, sent, c } = setup();
    c.request(0, 1100);
    c.request(0, 1200);
    expect(c.pendingCount).toBe(1);
    c.cancelAll();
    clock.advance(200);
    expect(sent.map((s) => s.pwm)).toEqual([1100]);
  });
});
