import { describe, expect, it } from 'vitest';
import {
  drainLimitS,
  highestHeld,
  lossByArm,
  rateSummary,
  ratesByArm,
  simProcesses,
  splitArms,
  spreadAgain,
  stepWhy,
} from '../lib/fleet-steps.ts';

describe('simProcesses', () => {
  it('keeps the arms in one process until one process would pass its budget', () => {
    expect(simProcesses(1, NaN, 2)).toBe(1); // nothing measured yet
    expect(simProcesses(50, 8, 2)).toBe(1); // 400 ms a second: within 500
    expect(simProcesses(100, 8, 2)).toBe(2); // 800 ms a second: spread
  });

  it('spreads over one process per core at most, and never more processes than arms', () => {
    expect(simProcesses(400, 8, 2)).toBe(2);
    expect(simProcesses(400, 8, 16)).toBe(7);
    expect(simProcesses(3, 900, 16)).toBe(3);
    expect(simProcesses(10, 8, 0)).toBe(1);
  });

  it('spreads over one process per core at once when the step before was behind', () => {
    expect(simProcesses(200, 1.5, 2, true)).toBe(2);
    expect(simProcesses(1, 1.5, 2, true)).toBe(1);
  });
});

describe('splitArms', () => {
  it('covers 1…N once, in consecutive ranges as even as can be', () => {
    expect(splitArms(10, 3)).toEqual([
      [1, 4],
      [5, 7],
      [8, 10],
    ]);
    expect(splitArms(1, 2)).toEqual([[1, 1]]);
  });
});

describe('rates', () => {
  it('gives each arm its samples a second between two snapshots, and the slowest arm', () => {
    const r = ratesByArm(
      { atMs: 1000, samples: { a: 10, b: 0 } },
      { atMs: 3000, samples: { a: 110, b: 80, c: 98 } },
    );
    expect(r).toEqual({ a: 50, b: 40, c: 49 });
    expect(rateSummary(r, 47.5)).toEqual({ min: 40, median: 49, slowest: 'b', short: 1, arms: 3 });
    expect(rateSummary({}).min).toBeNaN();
  });
});

describe('lossByArm', () => {
  const published = {
    a: { state: 100, health: 10, servos: 6 },
    b: { state: 50, health: 5, servos: 5 },
    c: { state: 10, health: 1, servos: 6 },
  };

  it('balances when every sample of every arm is stored as one point per servo', () => {
    const acc = lossByArm(published, { a: 660, b: 275, c: 66 });
    expect(acc).toMatchObject({ arms: 3, published: 1001, stored: 1001, lost: 0, extra: 0 });
    expect(acc.uneven).toEqual([]);
  });

  it('counts what each arm lacks, an arm never stored, and a surplus apart', () => {
    const acc = lossByArm(published, { a: 600, b: 280, x: 3 });
    expect(acc.lost).toBe(60 + 66);
    expect(acc.extra).toBe(5 + 3);
    // A surplus on one arm does not hide a loss on another.
    expect(acc.stored).toBe(883);
    expect(acc.uneven.map((u) => u.arm)).toEqual(['c', 'a', 'b', 'x']);
  });
});

describe('stepWhy', () => {
  const even = lossByArm({ a: { state: 250, health: 5, servos: 6 } }, { a: 1530 });
  const atRate = { min: 49.2, median: 49.8, slowest: 'a', short: 0, arms: 1 };
  const drain = { drainS: 2.5, drainLimitS: drainLimitS(1, 7) };

  it('passes a step that stored everything at the rate', () => {
    expect(stepWhy({ loss: even, dropped: 0, rateHz: 50, rates: atRate, ...drain })).toBe('');
  });

  it('says what was lost, dropped and how slow the slowest arm was, all of it', () => {
    const short = lossByArm({ a: { state: 250, health: 5, servos: 6 } }, { a: 1500 });
    const why = stepWhy({
      loss: short,
      dropped: 7,
      rateHz: 50,
      rates: { min: 31.5, median: 44, slowest: 'a', short: 1, arms: 1 },
      drainS: 12.25,
      drainLimitS: drainLimitS(1, 20),
    });
    expect(why).toBe(
      '30 of 1530 points lost (1 of 1 arms short); 7 points dropped by the middleware; stored 12.3 s after the arms stopped (limit 6.0 s); simulators below 50 Hz: 1 of 1 arms under 47.5 Hz, slowest a 31.5 Hz, median 44.0 Hz',
    );
  });

  it('fails a step whose rate was never measured', () => {
    expect(
      stepWhy({ loss: even, dropped: 0, rateHz: 50, rates: rateSummary({}), ...drain }),
    ).toMatch(/below 50 Hz/);
  });
});

describe('spreadAgain', () => {
  const slow =
    'simulators below 50 Hz: 400 of 400 arms under 47.5 Hz, slowest f9 24.9 Hz, median 27.3 Hz';

  it('runs a step again over one process per core when the sims alone fell short', () => {
    expect(spreadAgain({ why: slow, lost: 0, extra: 0, processes: 1 }, 2)).toBe(true);
    expect(spreadAgain({ why: slow, lost: 0, extra: 0, processes: 2 }, 2)).toBe(false);
  });

  it('not when the step lost points or failed for anything else', () => {
    expect(
      spreadAgain({ why: `3 of 9 points lost; ${slow}`, lost: 3, extra: 0, processes: 1 }, 2),
    ).toBe(false);
    expect(
      spreadAgain(
        {
          why: 'stored 9.0 s after the arms stopped (limit 3.3 s)',
          lost: 0,
          extra: 0,
          processes: 1,
        },
        2,
      ),
    ).toBe(false);
    expect(spreadAgain({ why: '', lost: 0, extra: 0, processes: 1 }, 2)).toBe(false);
  });
});

describe('highestHeld', () => {
  it('is the last passing step before the first failing one', () => {
    const s = [{ pass: true }, { pass: true }, { pass: false }, { pass: true }];
    expect(highestHeld(s)).toBe(s[1]);
    expect(highestHeld([{ pass: false }])).toBeUndefined();
  });
});
