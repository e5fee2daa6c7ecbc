import { describe, expect, test } from 'vitest';
import { WINDOW_LADDER, windowCount, windowFor } from '../src/history/window.ts';

const MIN = 60_000;
const H = 3_600_000;
const T = Date.UTC(2024, 0, 1);

describe('windowFor', () => {
  test.each([
    ['5 min', 5 * MIN, '200ms'],
    ['1 h', H, '2s'],
    ['24 h', 24 * H, '1m'],
    ['7 d', 7 * 24 * H, '10m'],
    ['31 d', 31 * 24 * H, '30m'],
    ['10 s', 10_000, '5ms'],
    ['1 ms', 1, '1ms'],
  ])('%s → %s', (_name, span, text) => {
    expect(windowFor(T, T + span, 2000).text).toBe(text);
  });

  test('never more than maxPoints windows, and the step below would give more (epoch-aligned)', () => {
    for (const span of [1, 999, 1000, 4_000_001, 5 * MIN + 7, H - 1, 24 * H + 13, 31 * 24 * H]) {
      for (const start of [T, T + 1, T + 12_345, T + 599_999]) {
        const w = windowFor(start, start + span, 2000);
        expect(windowCount(start, start + span, w.ms)).toBeLessThanOrEqual(2000);
        const i = WINDOW_LADDER.indexOf(w);
        if (i > 0)
          expect(windowCount(start, start + span, WINDOW_LADDER[i - 1]!.ms)).toBeGreaterThan(2000);
      }
    }
  });

  test('an unaligned range counts its partial first and last windows', () => {
    expect(windowCount(1500, 3500, 1000)).toBe(3); // [1000,2000) [2000,3000) [3000,4000)
    expect(windowCount(1000, 3000, 1000)).toBe(2);
  });

  test('the ladder is ascending and every text matches its length', () => {
    const unit: Record<string, number> = { ms: 1, s: 1000, m: 60_000, h: 3_600_000, d: 86_400_000 };
    for (let i = 0; i < WINDOW_LADDER.length; i++) {
      const w = WINDOW_LADDER[i]!;
      const [, n, u] = /^(\d+)(ms|s|m|h|d)$/.exec(w.text)!;
      expect(Number(n) * unit[u!]!).toBe(w.ms);
      if (i > 0) expect(w.ms).toBeGreaterThan(WINDOW_LADDER[i - 1]!.ms);
    }
  });
});
