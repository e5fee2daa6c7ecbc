/** The one retry back-off rule: min, then `factor` times longer per failure, capped at max. */
import { describe, expect, it } from 'vitest';
import { backoffDelay, solveLinear } from '../src/index.ts';

describe('backoffDelay', () => {
  it('doubles from min after each failure and stops at max', () => {
    const b = { minMs: 500, maxMs: 10_000 };
    expect([0, 1, 2, 3, 4, 5, 6].map((n) => backoffDelay(n, b))).toEqual([
      500, 1000, 2000, 4000, 8000, 10_000, 10_000,
    ]);
  });

  it('grows by its own factor, and stays finite after very many failures', () => {
    expect(backoffDelay(2, { minMs: 100, maxMs: 5000, factor: 3 })).toBe(900);
    expect(backoffDelay(1e9, { minMs: 100, maxMs: 5000 })).toBe(5000);
    expect(backoffDelay(-1, { minMs: 100, maxMs: 5000 })).toBe(100);
  });
});

describe('solveLinear', () => {
  it('solves a small system and refuses a singular one', () => {
    expect(
      solveLinear(
        [
          [2, 1],
          [1, 3],
        ],
        [3, 5],
      ),
    ).toEqual([0.8, 1.4].map((v) => expect.closeTo(v, 9) as number));
    expect(
      solveLinear(
        [
          [1, 2],
          [2, 4],
        ],
        [1, 2],
      ),
    ).toBeNull();
  });

  it('refuses a system whose pivot is below the given size', () => {
    const a = [
      [1e-20, 0],
      [0, 1],
    ];
    expect(solveLinear(a, [1, 1])).toBeNull();
    expect(solveLinear(a, [1, 1], 1e-300)).toEqual([1e20, 1]);
  });
});
