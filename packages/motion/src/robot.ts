/**
 * One arm as the planner sees it: its profile, the pulse table, and the kinematics its profile
 * names (the analytic §4 solver for `analytic5`, the numeric DLS solver for `numeric`), behind
 * two calls: `tipPose` (FK of a pulse vector) and `solveTip` (IK of a tip target, seeded with a
 * pulse vector). Pulses here are exact (not rounded): a plan keeps them fractional so its FK is
 * exact, and only the wire frames round (`toMoveFrames`).
 */
import {
  NumericIkSolver,
  chainFk,
  createIkResult,
  forwardKinematics,
  solveIkInto,
  type ArmProfile,
  type Chain,
  type NumericTarget,
} from '@armtwin/ik';
import {
  armProfileFromProfile,
  jointFromServo,
  servoFromJoint,
  servoFromPwm,
  servoTable,
  type Profile,
  type ProfileServo,
  type ServoTableEntry,
} from '@armtwin/robot';
import { PWM_CENTRE, US_PER_DEG } from '@armtwin/protocol';

/** A tip target: position in mm (base frame, z up) and, optionally, the tool's pitch from horizontal (deg, −90 = down). */
export interface TipTarget {
  x: number;
  y: number;
  z: number;
  pitch?: number;
}

/** Where the tip is: position (mm) and the tool's pitch from horizontal (deg). */
export interface TipPose {
  x: number;
  y: number;
  z: number;
  pitch: number;
}

export interface MotionRobot {
  readonly profile: Profile;
  /** Pulse limits, speeds and home, in profile servo order. */
  readonly table: readonly ServoTableEntry[];
  /** Wire ids, profile order. */
  readonly ids: readonly number[];
  readonly kind: 'analytic5' | 'numeric';
  /** `analytic5`: what `solveIk` takes. */
  readonly arm?: ArmProfile;
  /** `numeric`: the chain (from `chainFromUrdf`) and a solver reused for every step. */
  readonly chain?: Chain;
  readonly solver?: NumericIkSolver;
}

/** Result of `solveTip`: a status code (0 = reached) and pulses in servo order (NaN = not on the IK chain). */
export interface TipSolution {
  code: number;
  pwm: number[];
}

const DEG = Math.PI / 180;

/**
 * The planner's view of a parsed profile. A `numeric` profile needs its chain
 * (`chainFromUrdf(profile, urdfText)`); an `analytic5` one does not.
 */
export function createMotionRobot(profile: Profile, chain?: Chain): MotionRobot {
  const table = servoTable(profile);
  const ids = table.map((s) => s.id);
  if (profile.ik.kind === 'analytic5') {
    const arm = armProfileFromProfile(profile);
    if (!arm) throw new Error(`profile ${profile.name}: analytic5 without ik.analytic5`);
    return { profile, table, ids, kind: 'analytic5', arm };
  }
  if (!chain) throw new Error(`profile ${profile.name}: a numeric profile needs its chain`);
  // Solve within the pulse limits (the joint limits rounded inwards to whole µs), so a solution
  // never needs clamping, which would move the tip off the path.
  const lower = Float64Array.from(chain.lower);
  const upper = Float64Array.from(chain.upper);
  chain.joints.forEach((j, k) => {
    const servo = profile.servos[j.servoIndex]!;
    const { minPwm, maxPwm } = table[j.servoIndex]!;
    const a = jointFromServo(servo, servoFromPwm(servo, minPwm));
    const b = jointFromServo(servo, servoFromPwm(servo, maxPwm));
    lower[k] = Math.max(lower[k]!, Math.min(a, b));
    upper[k] = Math.min(upper[k]!, Math.max(a, b));
  });
  const limited: Chain = { ...chain, lower, upper };
  return {
    profile,
    table,
    ids,
    kind: 'numeric',
    chain: limited,
    solver: new NumericIkSolver(limited),
  };
}

/** Exact (unrounded) pulse for a servo value (deg or mm): the inverse of `servoFromPwm`. */
export function exactPwmFromServo(servo: ProfileServo, s: number): number {
  if (servo.type === 'revolute') return PWM_CENTRE + servo.polarity * US_PER_DEG * s;
  const u = (s - servo.min) / (servo.max - servo.min);
  const span = servo.pulseMax - servo.pulseMin;
  return servo.polarity === 1 ? servo.pulseMin + u * span : servo.pulseMax - u * span;
}

/** `pwm` clamped into servo i's pulse limits. */
export function clampPwm(robot: MotionRobot, i: number, pwm: number): number {
  const s = robot.table[i]!;
  return Math.min(s.maxPwm, Math.max(s.minPwm, pwm));
}

const ikScratch = createIkResult();
const fkJoints = { q0: 0, theta5: 0, theta4: 0, theta3: 0 };
const fkPose = { x: 0, y: 0, z: 0, alpha: 0 };

/** Chain joint values (rad or m) of a pulse vector. */
function chainJoints(robot: MotionRobot, pwm: ArrayLike<number>): Float64Array {
  const chain = robot.chain!;
  return Float64Array.from(chain.joints, (j) => {
    const servo = robot.profile.servos[j.servoIndex]!;
    return jointFromServo(servo, servoFromPwm(servo, pwm[j.servoIndex]!));
  });
}

/** The 5-axis arm's §4 joint angles (degrees) of a pulse vector (servo order), into `out`. */
export function analyticJointsInto<
  T extends { q0: number; theta5: number; theta4: number; theta3: number },
>(robot: MotionRobot, pwm: ArrayLike<number>, out: T): T {
  const servos = robot.profile.servos;
  const arm = robot.arm!;
  const joint = (i: number) =>
    servoFromPwm(servos[i]!, pwm[i]!) + (arm.servos[i]?.jointOffsetDeg ?? 0);
  out.q0 = joint(0);
  out.theta5 = joint(1);
  out.theta4 = joint(2);
  out.theta3 = joint(3);
  return out;
}

/** FK: where the tip is for these pulses (servo order). */
export function tipPose(robot: MotionRobot, pwm: ArrayLike<number>): TipPose {
  if (robot.kind === 'analytic5') {
    const p = forwardKinematics(analyticJointsInto(robot, pwm, fkJoints), robot.arm!, fkPose);
    return { x: p.x, y: p.y, z: p.z, pitch: p.alpha };
  }
  const m = chainFk(robot.chain!, chainJoints(robot, pwm));
  const [ax, ay, az] = robot.solver!.options.toolAxis;
  const wz = m[2]! * ax + m[6]! * ay + m[10]! * az;
  return { x: m[12]!, y: m[13]!, z: m[14]!, pitch: Math.asin(Math.max(-1, Math.min(1, wz))) / DEG };
}

/** Horizontal heading (rad) of the tool axis for these pulses (numeric arms; +x when vertical). */
function toolHeading(robot: MotionRobot, pwm: ArrayLike<number>): number {
  const m = chainFk(robot.chain!, chainJoints(robot, pwm));
  const [ax, ay, az] = robot.solver!.options.toolAxis;
  const wx = m[0]! * ax + m[4]! * ay + m[8]! * az;
  const wy = m[1]! * ax + m[5]! * ay + m[9]! * az;
  return Math.hypot(wx, wy) < 1e-6 ? 0 : Math.atan2(wy, wx);
}

/**
 * IK: pulses that put the tip at `target`, seeded with `seed` (the pulses the arm is at, or
 * the previous step's). `analytic5`: §4's solver (pitch searched when not given; codes 0–8).
 * `numeric`: position only, or, with a pitch, position + tool axis pointing at that pitch in
 * the vertical plane of the seed's tool heading (codes 0, 2, 9, 10). Pulses are exact, clamped
 * to the limits, NaN for servos the IK does not drive (wrist roll, gripper).
 */
export function solveTip(
  robot: MotionRobot,
  target: TipTarget,
  seed: ArrayLike<number>,
  heading?: number,
): TipSolution {
  const servos = robot.profile.servos;
  const pwm = new Array<number>(servos.length).fill(NaN);
  if (robot.kind === 'analytic5') {
    const arm = robot.arm!;
    const r = solveIkInto(ikScratch, target.x, target.y, target.z, target.pitch, arm);
    if (r.code !== 0) return { code: r.code, pwm };
    for (let i = 0; i < 4; i++)
      pwm[i] = clampPwm(robot, i, exactPwmFromServo(servos[i]!, r.servoAngles[i]!));
    return { code: 0, pwm };
  }
  const chain = robot.chain!;
  const t: NumericTarget = { mode: 'position', x: target.x, y: target.y, z: target.z };
  if (target.pitch !== undefined) {
    const psi = heading ?? toolHeading(robot, seed);
    const p = target.pitch * DEG;
    t.mode = 'axis';
    t.axis = [Math.cos(p) * Math.cos(psi), Math.cos(p) * Math.sin(psi), Math.sin(p)];
  }
  const r = robot.solver!.solve(t, chainJoints(robot, seed));
  if (r.code !== 0) return { code: r.code, pwm };
  chain.joints.forEach((j, k) => {
    const servo = servos[j.servoIndex]!;
    pwm[j.servoIndex] = clampPwm(
      robot,
      j.servoIndex,
      exactPwmFromServo(servo, servoFromJoint(servo, r.joints[k]!)),
    );
  });
  return { code: 0, pwm };
}

/** The heading `solveTip` uses for pitch targets on a numeric arm, fixed once per plan. */
export function planHeading(robot: MotionRobot, pwm: ArrayLike<number>): number | undefined {
  return robot.kind === 'numeric' ? toolHeading(robot, pwm) : undefined;
}
