import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { createIkResult, isWithinLimits, solveIk, solveIkInto } from '../src/index.ts';

const anyNumber = fc.oneof(
  fc.double(), // includes NaN, ±Infinity, -0 and huge values
  fc.double({ min: -600, max: 600, noNaN: true }),
);

describe('solveIk on arbitrary input', () => {
  it('never throws and returns an integer code in 0..8; code 0 means sendable pulses', () => {
    fc.assert(
      fc.property(
        anyNumber,
        anyNumber,
        anyNumber,
        fc.option(anyNumber, { nil: undefined }),
        (x, y, z, a) => {
          const r = solveIk(x, y, z, a);
          expect(Number.isInteger(r.code)).toBe(true);
          expect(r.code).toBeGreaterThanOrEqual(0);
          expect(r.code).toBeLessThanOrEqual(8);
          if (r.code === 0) {
            r.pwm.forEach((pwm, id) => expect(isWithinLimits(id, pwm)).toBe(true));
            expect(Number.isInteger(r.alpha) || a !== undefined).toBe(true);
          } else {
            expect(r.pwm.every(Number.isNaN)).toBe(true);
          }
          if (a !== undefined) expect(r.alpha).toBe(a);
        },
      ),
      { numRuns: 2000 },
    );
  });

  it('solveIkInto reuses its result and agrees with solveIk', () => {
    const out = createIkResult();
    fc.assert(
      fc.property(
        anyNumber,
        anyNumber,
        anyNumber,
        fc.option(anyNumber, { nil: undefined }),
        (x, y, z, a) => {
          const joints = out.joints;
          expect(solveIkInto(out, x, y, z, a)).toBe(out);
          expect(out.joints).toBe(joints);
          expect(out).toEqual(solveIk(x, y, z, a));
        },
      ),
      { numRuns: 300 },
    );
  });
});
