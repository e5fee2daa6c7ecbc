/**
 * The analytic IK of PROTOCOL.md §4, as the controller computes it: elbow-up solution, checks
 * in the order 1, 2, 3, 5, 4, 6, 7 with a 1e-9 tolerance, then (our addition) 8, base limit.
 * Degrees and mm throughout. The hot path (one solve, or the 181-step α search) allocates
 * nothing beyond the result object, and `solveIkInto` reuses a result to allocate nothing.
 */
import { DEMO_ARM, type ArmProfile, type ServoSpec } from './arm.ts';
import { pwmFromJoints, servoAnglesFromJoints, type Joints, type Quad } from './fk.ts';

/**
 * Status codes and the words the HUD shows for them. 0–7 are §4's. 8 is ours: §4 computes
 * q0 = atan2(y, x) but lists no code for the base's ±135° limit, so a target §4 would accept
 * whose yaw is outside that limit gets 8. It is checked last, so every target §4 rejects keeps
 * exactly §4's code; 8 only ever replaces a 0.
 */
export const IK_CODES = {
  0: 'accepted, moving',
  1: 'wrist below the floor',
  2: 'out of reach',
  3: 'no triangle at the shoulder',
  4: 'elbow (forearm) limit',
  5: 'no triangle at the elbow',
  6: 'shoulder (upper arm) limit',
  7: 'wrist limit',
  8: 'base (yaw) limit',
} as const;

export type IkCode = keyof typeof IK_CODES;

/** Slack allowed in every comparison (§4), so that poses on a limit, like home, pass. */
export const IK_TOLERANCE = 1e-9;

/** First and last pitch tried when α is not given, in 1° steps (§4). */
export const ALPHA_SEARCH_FROM = -90;
export const ALPHA_SEARCH_TO = 90;

export interface IkResult {
  /** Status code of §4 (0 = accepted), or 8 for the base limit. */
  code: IkCode;
  /** The pitch used: the one given, the first found by the search, or −90 if none passed. */
  alpha: number;
  /**
   * Joint angles, degrees. With code 0, the solution. With codes 4, 6, 7, 8, the rejected
   * solution (so a HUD can draw it and show which joint is over its limit). With codes 1, 2,
   * 3, 5 there is no solution: q0 is still the target's yaw, the other three are NaN.
   */
  joints: Joints;
  /** Servo angles of 000–003 (s000 = q0, s001 = θ5 − 90, s002 = θ4, s003 = θ3); same rule. */
  servoAngles: Quad;
  /** Pulse widths of 000–003, integer µs, only when code is 0; otherwise all NaN. */
  pwm: Quad;
}

/** A fresh result, to pass to `solveIkInto`. */
export function createIkResult(): IkResult {
  return {
    code: 0,
    alpha: 0,
    joints: { q0: NaN, theta5: NaN, theta4: NaN, theta3: NaN },
    servoAngles: [NaN, NaN, NaN, NaN],
    pwm: [NaN, NaN, NaN, NaN],
  };
}

const DEG = Math.PI / 180;
const RAD = 180 / Math.PI;
const TOL = IK_TOLERANCE;

/** Whether joint angle `v` is within the servo's limits shifted to joint space, with slack. */
function jointOk(v: number, spec: ServoSpec | undefined): boolean {
  if (spec === undefined) return true;
  return (
    v >= spec.minDeg + spec.jointOffsetDeg - TOL && v <= spec.maxDeg + spec.jointOffsetDeg + TOL
  );
}

/** No solution for this α: fill the result's angles with NaN (q0 kept) and return `code`. */
function reject(out: IkResult, code: IkCode, arm: ArmProfile): IkCode {
  const j = out.joints;
  j.theta5 = j.theta4 = j.theta3 = NaN;
  out.servoAngles.fill(NaN);
  out.servoAngles[0] = j.q0 - (arm.servos[0]?.jointOffsetDeg ?? 0);
  out.pwm.fill(NaN);
  out.code = code;
  return code;
}

/** One α. `q0` (degrees) and `r` are the target's yaw and distance from the base axis. */
function solveAt(
  out: IkResult,
  arm: ArmProfile,
  q0: number,
  r: number,
  z: number,
  alpha: number,
): IkCode {
  const { l0, l1, l2, l3 } = arm.links;
  out.alpha = alpha;
  out.joints.q0 = q0;
  const yp = r - l3 * Math.cos(alpha * DEG);
  const zp = z - l0 - l3 * Math.sin(alpha * DEG);
  if (zp < -l0 - TOL) return reject(out, 1, arm);
  const d = Math.sqrt(yp * yp + zp * zp);
  if (d > l1 + l2 + TOL) return reject(out, 2, arm);
  if (d === 0) return reject(out, 3, arm);
  const cosA = (l1 * l1 + d * d - l2 * l2) / (2 * l1 * d);
  if (Math.abs(cosA) > 1 + TOL) return reject(out, 3, arm);
  const cosB = (l1 * l1 + l2 * l2 - d * d) / (2 * l1 * l2);
  if (Math.abs(cosB) > 1 + TOL) return reject(out, 5, arm);
  const a = Math.acos(Math.min(1, Math.max(-1, cosA))) * RAD;
  const b = Math.acos(Math.min(1, Math.max(-1, cosB))) * RAD;
  const j = out.joints;
  j.theta5 = Math.atan2(zp, yp) * RAD + a;
  j.theta4 = b - 180;
  j.theta3 = alpha - j.theta5 - j.theta4;
  servoAnglesFromJoints(j, arm, out.servoAngles);
  out.pwm.fill(NaN);
  const sv = arm.servos;
  let code: IkCode = 0;
  if (!jointOk(j.theta4, sv[2])) code = 4;
  else if (!jointOk(j.theta5, sv[1])) code = 6;
  else if (!jointOk(j.theta3, sv[3])) code = 7;
  else if (!jointOk(q0, sv[0])) code = 8;
  else pwmFromJoints(j, arm, out.pwm);
  out.code = code;
  return code;
}

/**
 * Solve into `out` (no allocation). With `alpha` undefined, tries α = −90, −89, …, 90 and keeps
 * the first that passes; if none does, `out` holds the attempt at α = −90. A non-finite x, y,
 * z or α (NaN, ±Infinity) gives code 2, out of reach, with every angle NaN.
 */
export function solveIkInto(
  out: IkResult,
  x: number,
  y: number,
  z: number,
  alpha?: number,
  arm: ArmProfile = DEMO_ARM,
): IkResult {
  const search = alpha === undefined;
  const a0 = search ? ALPHA_SEARCH_FROM : alpha;
  if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z) || !Number.isFinite(a0)) {
    out.alpha = a0;
    out.joints.q0 = NaN;
    reject(out, 2, arm);
    return out;
  }
  const q0 = Math.atan2(y, x) * RAD;
  const r = Math.sqrt(x * x + y * y);
  // The base check does not depend on α: when it fails, no α can pass.
  if (search && jointOk(q0, arm.servos[0])) {
    for (let a = ALPHA_SEARCH_FROM; a <= ALPHA_SEARCH_TO; a++) {
      if (solveAt(out, arm, q0, r, z, a) === 0) return out;
    }
  }
  solveAt(out, arm, q0, r, z, a0);
  return out;
}

/**
 * IK for a gripper tip at (x, y, z) mm with pitch `alpha` degrees (searched when omitted) on
 * `arm` (the demo arm by default). Never throws. See `IkResult` for what each field holds.
 */
export function solveIk(
  x: number,
  y: number,
  z: number,
  alpha?: number,
  arm: ArmProfile = DEMO_ARM,
): IkResult {
  return solveIkInto(createIkResult(), x, y, z, alpha, arm);
}

/** The HUD's words for a status code (`unknown code n` for one outside 0–8). */
export function ikCodeMessage(code: number): string {
  return (IK_CODES as Record<number, string>)[code] ?? `unknown code ${code}`;
}
