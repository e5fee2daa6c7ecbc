/**
 * The Cartesian panel's local IK for any profile: the §4 solver for an `analytic5` arm (as
 * before: `$KMS` is what its controller understands), the planner's numeric IK otherwise (the
 * target then goes out as a motion request, which any armtwin arm serves). Pure.
 */
import { ikCodeMessage, solveIk, type ArmProfile } from '@armtwin/ik';
import {
  CODE_BELOW_FLOOR,
  CODE_IN_ZONE,
  CODE_SELF_COLLISION,
  checkFloor,
  checkZonesMove,
  motionCodeMessage,
  solveTip,
  tipPose,
  type MotionRobot,
} from '@armtwin/motion';
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
  /** With code 24: what is below the floor, in words (`tip 50.0 mm below the floor …`). */
  floor?: string;
  /**
   * With code 25 or 26: the link that would collide, in words (`hand 12.0 mm into zone
   * "table"`), and the URDF joint whose child link the ghost paints red.
   */
  zone?: { message: string; joint: string };
}

/**
 * Where the Cartesian fields start: the tip of `motion` at `pwm` (where the arm is), or at its
 * home pose when the arm has not reported; mm to 0.1, pitch blank. Blank fields without a robot.
 */
export function startFields(
  motion: MotionRobot | null,
  pwm: ArrayLike<number>,
): { x: string; y: string; z: string; pitch: string } {
  if (!motion) return { x: '', y: '', z: '', pitch: '' };
  const now = Array.from(pwm);
  const at =
    now.length === motion.ids.length && now.every(Number.isFinite)
      ? now
      : motion.table.map((s) => s.homePwm);
  const tip = tipPose(motion, at);
  const mm = (v: number) => String(Math.round(v * 10) / 10 + 0);
  return { x: mm(tip.x), y: mm(tip.y), z: mm(tip.z), pitch: '' };
}

/** Codes the page (and the controller's `$KMS` reply) gives for keep-out refusals. */
const KEEP_OUT_CODES: readonly number[] = [CODE_BELOW_FLOOR, CODE_IN_ZONE, CODE_SELF_COLLISION];

export function codeWords(code: number, via: TargetSolution['via']): string {
  return via === 'kms' && !KEEP_OUT_CODES.includes(code)
    ? ikCodeMessage(code)
    : motionCodeMessage(code);
}

/**
 * The floor (docs/protocol.md, "The floor"): a solution that would put the tool or a joint
 * under it becomes code 24; one whose path takes a link into a keep-out zone 25, onto another
 * link 26: refused here before anything is sent (the arm refuses it too).
 */
function floorChecked(
  r: TargetSolution,
  motion: MotionRobot | null,
  seed: ArrayLike<number>,
): TargetSolution {
  if (r.code !== 0 || !motion) return r;
  const pwm = r.pwm.map((p, i) =>
    Number.isNaN(p) ? (Number.isFinite(seed[i]) ? seed[i]! : motion.table[i]!.homePwm) : p,
  );
  const c = checkFloor(motion, pwm);
  if (!c.ok) return { ...r, code: CODE_BELOW_FLOOR, floor: c.message };
  // Keep-out zones and self-collision along the straight joint path the controller will take
  // from where the arm is (docs/protocol.md, "Keep-out zones").
  const from = Array.from(seed, (p, i) => (Number.isFinite(p) ? p : motion.table[i]!.homePwm));
  const z = checkZonesMove(motion, from, pwm);
  if (z.ok) return r;
  const code = z.kind === 'zone' ? CODE_IN_ZONE : CODE_SELF_COLLISION;
  return { ...r, code, zone: { message: z.message, joint: z.joint } };
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
  return floorChecked(solveAny(x, y, z, pitch, arm, motion, seed), motion, seed);
}

function solveAny(
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
