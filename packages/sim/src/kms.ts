/**
 * The simulated demo arm's `$KMS` (PROTOCOL.md §4) as a solver for the controller core: the
 * analytic IK on servos 000–003 of the sim's servo table, pulses by servo index (NaN = leave).
 * A profile's arm brings its own solver (`numericKms`, profile.ts); the core checks the limits
 * and the keep-out rules of either.
 */
import { solveIk, type ArmProfile } from '@armtwin/ik';
import type { KmsSolver } from '@armtwin/controller';

export function analyticKms(arm: ArmProfile): KmsSolver {
  return (x, y, z, alpha) => {
    const r = solveIk(x, y, z, alpha, arm);
    const pwm = new Array<number>(arm.servos.length).fill(NaN);
    if (r.code === 0) for (let j = 0; j < 4 && j < pwm.length; j++) pwm[j] = r.pwm[j]!;
    return { code: r.code, pwm };
  };
}
