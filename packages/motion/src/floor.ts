/**
 * The floor, the first keep-out zone (docs/protocol.md, "The floor"): no pose may put the tool
 * point or any joint's origin below the plane z = `ik.floorZ` of the arm's base frame (default
 * 0: §4's floor, and the plane the HUD draws at the URDF's base). One pure check, used by the
 * page before it sends and again by the controllers (the simulator, the bus gateway) before
 * they move. Allocation-light: scratch objects are made once per module or per chain.
 * Only poses are checked (a plan's every sample, a controller's goal pose), not the straight
 * joint-space path between two goals a controller interpolates.
 */
import {
  armPoints,
  chainFkFrames,
  createArmPoints,
  createFkFrames,
  type Chain,
  type FkFrames,
} from '@armtwin/ik';
import { jointFromServo, servoFromPwm } from '@armtwin/robot';
import type { Plan } from './plan.ts';
import { analyticJointsInto, type MotionRobot } from './robot.ts';

/** The floor's height in the base frame when a profile does not say, mm. */
export const DEFAULT_FLOOR_Z = 0;
/** Slack below the floor still accepted, mm (rounding: a pose exactly on the floor passes). */
export const FLOOR_TOLERANCE_MM = 1e-6;

/** What the floor check found: `ok`, or the lowest point under the floor. */
export type FloorCheck =
  | { ok: true }
  | {
      ok: false;
      /** `tip`, or the joint (URDF joint name, or §4's `elbow` / `wrist`) whose origin is low. */
      point: string;
      /** Its height, mm, base frame. */
      z: number;
      /** The floor's height, mm. */
      floorZ: number;
      /** In words, for a refusal: `tip 300.0 mm below the floor (z −300.0 < 0)`. */
      message: string;
    };

const OK: FloorCheck = { ok: true };
const joints = { q0: 0, theta5: 0, theta4: 0, theta3: 0 };
const points = createArmPoints();
const frames = new WeakMap<Chain, { q: Float64Array; fk: FkFrames }>();

/** The floor of this robot, mm in its base frame. */
export function floorZ(robot: MotionRobot): number {
  return robot.profile.ik.floorZ ?? DEFAULT_FLOOR_Z;
}

function below(point: string, z: number, floor: number): FloorCheck {
  const depth = (floor - z).toFixed(1);
  return {
    ok: false,
    point,
    z,
    floorZ: floor,
    message: `${point} ${depth} mm below the floor (z ${z.toFixed(1)} < ${floor})`,
  };
}

/**
 * Whether the pose of these pulses (profile servo order) keeps the tool point and every joint
 * origin on or above the floor; when not, the lowest of them. A pose with a servo of the IK
 * chain unknown (NaN) cannot be checked and passes (the servo limits refuse it elsewhere).
 */
export function checkFloor(robot: MotionRobot, pwm: ArrayLike<number>): FloorCheck {
  const floor = floorZ(robot);
  const servos = robot.profile.servos;
  let low = '';
  let lowZ = Infinity;
  const see = (name: string, z: number) => {
    if (z < lowZ) {
      lowZ = z;
      low = name;
    }
  };
  if (robot.kind === 'analytic5') {
    if (!Object.values(analyticJointsInto(robot, pwm, joints)).every(Number.isFinite)) return OK;
    armPoints(joints, robot.arm!, points);
    for (const name of ['tip', 'wrist', 'elbow'] as const) see(name, points[name].z);
  } else {
    const chain = robot.chain!;
    let s = frames.get(chain);
    if (!s) frames.set(chain, (s = { q: new Float64Array(chain.dof), fk: createFkFrames(chain) }));
    for (let k = 0; k < chain.dof; k++) {
      const j = chain.joints[k]!;
      const servo = servos[j.servoIndex]!;
      const v = jointFromServo(servo, servoFromPwm(servo, pwm[j.servoIndex]!));
      if (!Number.isFinite(v)) return OK;
      s.q[k] = v;
    }
    const fk = chainFkFrames(chain, s.q, s.fk);
    see('tip', fk.tip[14]!);
    for (let k = chain.dof - 1; k >= 0; k--) see(chain.joints[k]!.name, fk.points[3 * k + 2]!);
  }
  return lowZ < floor - FLOOR_TOLERANCE_MM ? below(low, lowZ, floor) : OK;
}

/**
 * The controller's rule for a move from pose `from` to pose `to` (pulses, servo order): refused
 * when `to` is below the floor, unless `from` already was and `to` goes no lower (so an arm put
 * below the floor can always be brought back up).
 */
export function checkFloorMove(
  robot: MotionRobot,
  from: ArrayLike<number>,
  to: ArrayLike<number>,
): FloorCheck {
  const after = checkFloor(robot, to);
  if (after.ok) return after;
  const before = checkFloor(robot, from);
  return !before.ok && after.z >= before.z - FLOOR_TOLERANCE_MM ? OK : after;
}

/**
 * The first sample of a plan that goes below the floor, with its index, or null. A plan that
 * starts below the floor (the arm was put there by hand, or the floor was moved) is checked at
 * its end only, so the arm can always be brought back up.
 */
export function planBelowFloor(
  robot: MotionRobot,
  plan: Plan,
): { sample: number; check: Extract<FloorCheck, { ok: false }> } | null {
  const samples = plan.samples;
  const last = samples.length - 1;
  if (!checkFloor(robot, samples[0]!.pwm).ok) {
    const c = checkFloorMove(robot, samples[0]!.pwm, samples[last]!.pwm);
    return c.ok ? null : { sample: last, check: c };
  }
  for (let i = 1; i <= last; i++) {
    const c = checkFloor(robot, samples[i]!.pwm);
    if (!c.ok) return { sample: i, check: c };
  }
  return null;
}
