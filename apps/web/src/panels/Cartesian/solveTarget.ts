/**
 * The Cartesian panel's local IK for any profile: the §4 solver for an `analytic5` arm (as
 * before: `$KMS` is what its controller understands), the planner's numeric IK otherwise (the
 * target then goes out as a motion request, which any armtwin arm serves). Pure.
 */
import { ikCodeMessage, solveIk, type ArmProfile } from '@armtwin/ik';
import { motionCodeMessage, solveTip, tipPose, type MotionRobot } from '@armtwin/motion';
import { angleFromPwm } from '@armtwin/protocol';

export interface TargetSolution {
  /** 0 = reachable, else the IK's code. */
  code: number;
  /** Store angles (degrees) of the solution per servo, NaN where it leaves a servo be. */
  servoAngles: number[];
  /** The tool's pitch at the solution, degrees (NaN when unreachable). */
  alpha: number;
  /** Pulses of the solution (NaN where it leaves a servo be). */
  pwm: number[];
  /** How the target goes out: `$KMS` (analytic arm) or a motion request. */
  via: 'kms' | 'request';
}

export function codeWords(code: number, via: TargetSolution['via']): string {
  return via === 'kms' ? ikCodeMessage(code) : motionCodeMessage(code);
}

export function solveTarget(
  x: number,
  y: number,
  z: number,
  pitch: number | undefined,
  arm: ArmProfile,
  motion: MotionRobot | null,
  seed: ArrayLike<number>,
): TargetSolution {
  if (!motion || motion.kind === 'analytic5') {
    const r = solveIk(x, y, z, pitch, motion?.arm ?? arm);
    return {
      code: r.code,
      servoAngles: [...r.servoAngles],
      alpha: r.alpha,
      pwm: [...r.pwm],
      via: 'kms',
    };
  }
  const from = Array.from(seed, (p, i) => (Number.isFinite(p) ? p : motion.table[i]!.homePwm));
  const target = pitch === undefined ? { x, y, z } : { x, y, z, pitch };
  const r = solveTip(motion, target, from);
  const pwm = r.pwm;
  const servoAngles = pwm.map((p, i) =>
    Number.isNaN(p) ? NaN : angleFromPwm(p, arm.servos[i]?.polarity === -1 ? -1 : 1),
  );
  const alpha =
    r.code === 0
      ? tipPose(
          motion,
          pwm.map((p, i) => (Number.isNaN(p) ? from[i]! : p)),
        ).pitch
      : NaN;
  return { code: r.code, servoAngles, alpha, pwm, via: 'request' };
}
