import { describe, expect, test } from 'vitest';
import { boundedRatio, stepVerdict } from '../lib/zero-loss.ts';

describe('the ratio of two zero-loss limits', () => {
  const at = (rate: number) => ({ rate, limit: true });
  const past = (rate: number) => ({ rate, limit: false }); // ended at the publisher or the list

  test('both at their own limits: the ratio, met or not', () => {
    expect(boundedRatio(at(120), at(40), 3)).toEqual({ ratio: 3, kind: 'exact', met: true });
    expect(boundedRatio(at(80), at(40), 3)).toMatchObject({ kind: 'exact', met: false });
  });

  test('only the other at its limit: a lower bound, which can meet the target, never miss it', () => {
    // the run of 2026-11-27 17:39: middleware 150,000 frames/s (publisher's end), Telegraf 40,000
    expect(boundedRatio(past(150_000), at(40_000), 3)).toEqual({
      ratio: 3.75,
      kind: 'at least',
      met: true,
    });
    expect(boundedRatio(past(64_000), at(32_000), 3)).toMatchObject({
      kind: 'at least',
      met: null,
    });
  });

  test('only this one at its limit: an upper bound, which can miss the target, never meet it', () => {
    expect(boundedRatio(at(64_000), past(32_000), 3)).toMatchObject({
      kind: 'at most',
      met: false,
    });
    expect(boundedRatio(at(128_000), past(32_000), 3)).toMatchObject({
      kind: 'at most',
      met: null,
    });
  });

  test('neither at its limit, or nothing passed: no ratio', () => {
    expect(boundedRatio(past(64_000), past(64_000), 3)).toMatchObject({ kind: 'none', met: null });
    expect(boundedRatio(at(64_000), at(0), 3)).toMatchObject({ kind: 'none', met: null });
  });
});

describe('a step of a zero-loss ramp', () => {
  test('fails on missing points first, then a publisher behind, then a slow backlog', () => {
    const f = {
      rate: 1000,
      sent: 1000,
      sendS: 1,
      missing: 0,
      unit: 'points',
      drainS: 1,
      drainLimitS: 3,
    };
    expect(stepVerdict(f)).toBe('');
    expect(stepVerdict({ ...f, missing: 6 })).toBe('6 points missing');
    expect(stepVerdict({ ...f, sendS: 2 })).toBe('publisher reached 500/s only');
    expect(stepVerdict({ ...f, drainS: 3.5 })).toBe('backlog took 3.5 s to write');
  });
});
