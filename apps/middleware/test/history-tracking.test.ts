import { describe, expect, test } from 'vitest';
import { commandedAt, trackingStats, type Command } from '../src/history/tracking.ts';
import type { Sample } from '../src/history/alarms.ts';

const s = (...pairs: [number, number][]): Sample[] => pairs.map(([t, v]) => ({ t, v }));

describe('commandedAt', () => {
  const cmd: Command = { t: 1000, angle: 30, ms: 1000 };
  test('ramps linearly from the start position to the target over ms, then holds', () => {
    expect(commandedAt(cmd, 10, 1000)).toBe(10);
    expect(commandedAt(cmd, 10, 1250)).toBe(15);
    expect(commandedAt(cmd, 10, 1500)).toBe(20);
    expect(commandedAt(cmd, 10, 2000)).toBe(30);
    expect(commandedAt(cmd, 10, 9000)).toBe(30);
  });
  test('ms = 0 is a step', () => {
    expect(commandedAt({ t: 0, angle: -45, ms: 0 }, 90, 0)).toBe(-45);
  });
});

describe('trackingStats', () => {
  test('hand-computed: a ramp from the last actual sample, then a hold', () => {
    // Actual samples every 100 ms; command at t=150: go to 20° in 400 ms, from the sample at
    // t=100 (0°). Reference: t=200 → 2.5, 300 → 7.5, 400 → 12.5, 500 → 17.5, 600 → 20, 700 → 20.
    const actual = s(
      [0, 0],
      [100, 0],
      [200, 1],
      [300, 8],
      [400, 12],
      [500, 19],
      [600, 21],
      [700, 20],
    );
    const r = trackingStats('001', [{ t: 150, angle: 20, ms: 400 }], actual, 0, 1000);
    // errors: 1.5, 0.5, 0.5, 1.5, 1, 0 → sum 5, n 6
    expect(r.samples).toBe(6);
    expect(r.meanAbsError).toBeCloseTo(5 / 6, 12);
    expect(r.maxAbsError).toBeCloseTo(1.5, 12);
    expect(r.maxAt).toBe(200);
  });

  test('samples before the first command are not scored; a sample at the command time starts the move', () => {
    const actual = s([0, 5], [100, 5], [200, 7.5], [300, 10]);
    const r = trackingStats('002', [{ t: 100, angle: 10, ms: 200 }], actual, 0, 1000);
    // from = 5 (sample at t=100). ref: 100 → 5, 200 → 7.5, 300 → 10: all exact.
    expect(r).toEqual({ id: '002', samples: 3, meanAbsError: 0, maxAbsError: 0, maxAt: 100 });
  });

  test('a new command restarts from the last actual sample before it', () => {
    const cmds: Command[] = [
      { t: 0, angle: 10, ms: 0 },
      { t: 250, angle: 30, ms: 100 },
    ];
    const actual = s([0, 10], [200, 11], [300, 20], [400, 29]);
    // t=0: 0 (step to 10); 200: |11-10| = 1; 300: from 11 at 250, half way → 20.5 → 0.5; 400: 30 → 1
    const r = trackingStats('003', cmds, actual, 0, 1000);
    expect(r.samples).toBe(4);
    expect(r.meanAbsError).toBeCloseTo(2.5 / 4, 12);
    expect(r.maxAbsError).toBe(1);
  });

  test('only samples inside [start, stop) are scored; earlier ones still anchor the move', () => {
    const actual = s([0, 0], [100, 0], [200, 4], [300, 10]);
    // command at 50 to 10° over 200 ms from 0: ref(100) = 2.5, ref(200) = 7.5, ref(300) = 10
    const r = trackingStats('004', [{ t: 50, angle: 10, ms: 200 }], actual, 150, 300);
    expect(r).toEqual({ id: '004', samples: 1, meanAbsError: 3.5, maxAbsError: 3.5, maxAt: 200 });
  });

  test('a command with no earlier actual sample is a step', () => {
    const r = trackingStats('005', [{ t: 0, angle: 10, ms: 1000 }], s([500, 6]), 0, 1000);
    expect(r.maxAbsError).toBe(4);
  });

  test('no commands or no samples: count 0, figures null', () => {
    expect(trackingStats('006', [], s([0, 1]), 0, 10)).toEqual({
      id: '006',
      samples: 0,
      meanAbsError: null,
      maxAbsError: null,
      maxAt: null,
    });
    expect(trackingStats('006', [{ t: 0, angle: 1, ms: 0 }], [], 0, 10).samples).toBe(0);
  });
});
