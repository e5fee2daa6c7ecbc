import { describe, expect, it } from 'vitest';
import { leastSquares, slopeFrom } from '../lib/slope.ts';

describe('leastSquares', () => {
  it('recovers an exact line', () => {
    const f = leastSquares([0, 1, 2, 3], [1, 3, 5, 7]);
    expect(f.slope).toBeCloseTo(2, 12);
    expect(f.intercept).toBeCloseTo(1, 12);
    expect(f.n).toBe(4);
  });

  it('is flat for a constant series and ignores non-finite pairs', () => {
    const f = leastSquares([0, 1, 2, 3], [5, NaN, 5, 5]);
    expect(f.slope).toBe(0);
    expect(f.n).toBe(3);
  });

  it('has no slope below two points or with one x', () => {
    expect(leastSquares([1], [2]).slope).toBeNaN();
    expect(leastSquares([1, 1], [2, 3]).slope).toBeNaN();
  });
});

describe('slopeFrom', () => {
  it('fits only from the given x on (the warm-up is left out)', () => {
    // A jump during warm-up (minutes 0–1), flat afterwards.
    const f = slopeFrom([0, 1, 2, 3, 4, 5], [10, 14, 16, 16, 16, 16], 2);
    expect(f.slope).toBe(0);
    expect(f.n).toBe(4);
  });
});
