import { describe, expect, it } from 'vitest';
import { histogram, percentile, percentileSorted, summarize } from '../lib/stats.ts';

describe('bench stats', () => {
  it('interpolates percentiles between ranks', () => {
    expect(percentile([4, 1, 3, 2], 50)).toBe(2.5);
    expect(percentile([1, 2, 3, 4, 5], 0)).toBe(1);
    expect(percentile([1, 2, 3, 4, 5], 100)).toBe(5);
    expect(percentileSorted([10, 20], 25)).toBe(12.5);
    const hundred = Array.from({ length: 101 }, (_, i) => i);
    expect(percentile(hundred, 99)).toBe(99);
    expect(percentile(hundred, 95)).toBe(95);
  });

  it('ignores NaN and is NaN when empty', () => {
    expect(percentile([NaN, 7], 50)).toBe(7);
    expect(Number.isNaN(percentile([], 50))).toBe(true);
    expect(Number.isNaN(summarize([]).mean)).toBe(true);
  });

  it('summarizes', () => {
    const s = summarize([3, 1, 2, 10]);
    expect(s).toMatchObject({ n: 4, mean: 4, min: 1, max: 10, p50: 2.5 });
    expect(s.p99).toBeCloseTo(9.79, 10);
  });

  it('bins samples, the last bin taking the overflow', () => {
    expect(histogram([0, 0.5, 1, 1.9, 2, 99, -1], 0, 2, 2)).toEqual([2, 4]);
  });
});
