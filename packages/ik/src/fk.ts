/**
 * Forward kinematics of PROTOCOL.md §4 and the joint ↔ servo ↔ pulse mappings.
 * All angles in degrees, lengths in mm, frame: z up, floor z = 0, base yaw 0 along +x.
 * Functions that return objects take an optional `out` to fill instead, so per-frame code
 * (the HUD's ghost arm) can call them without allocating.
 */
import { DEMO_ARM, type ArmProfile } from './arm.ts';
import { pwmFromAngle } from '@armtwin/protocol';

/** Joint angles of §4, degrees. */
export interface Joints {
  /** Base yaw, from +x towards +y. */
  q0: number;
  /** Shoulder: upper arm from horizontal. */
  theta5: number;
  /** Elbow: forearm relative to the upper arm (≤ 0 in the elbow-up solution). */
  theta4: number;
  /** Wrist pitch: gripper relative to the forearm. */
  theta3: number;
}

/** Servo angles or pulses of servos 000–003 (base, shoulder, elbow, wrist pitch). */
export type Quad = [number, number, number, number];

export interface Vec3 {
  x: number;
  y: number;
  z: number;
}

/** Tip position (mm) and gripper pitch α from horizontal (degrees). */
export interface Pose extends Vec3 {
  alpha: number;
}

/** The joints' positions in the world frame, mm, for drawing the arm. */
export interface ArmPoints {
  /** Shoulder axis, (0, 0, L0). */
  shoulder: Vec3;
  elbow: Vec3;
  /** Wrist centre (wrist pitch axis). */
  wrist: Vec3;
  /** Gripper tip. */
  tip: Vec3;
}

const DEG = Math.PI / 180;

function set(v: Vec3, c: number, s: number, h: number, z: number): void {
  v.x = h * c;
  v.y = h * s;
  v.z = z;
}

/** Fresh zeroed `ArmPoints`, to pass as `out`. */
export function createArmPoints(): ArmPoints {
  return {
    shoulder: { x: 0, y: 0, z: 0 },
    elbow: { x: 0, y: 0, z: 0 },
    wrist: { x: 0, y: 0, z: 0 },
    tip: { x: 0, y: 0, z: 0 },
  };
}

/**
 * Shoulder, elbow, wrist centre and tip positions: elbow = L1·(cos θ5, sin θ5) above the
 * shoulder, forearm heading θ5+θ4, gripper heading θ5+θ4+θ3, all rotated by q0.
 */
export function armPoints(
  j: Joints,
  arm: ArmProfile = DEMO_ARM,
  out: ArmPoints = createArmPoints(),
): ArmPoints {
  const { l0, l1, l2, l3 } = arm.links;
  const c = Math.cos(j.q0 * DEG);
  const s = Math.sin(j.q0 * DEG);
  const a1 = j.theta5 * DEG;
  const a2 = (j.theta5 + j.theta4) * DEG;
  const a3 = (j.theta5 + j.theta4 + j.theta3) * DEG;
  // (h, v): horizontal distance from the base axis and height above the shoulder axis.
  let h = l1 * Math.cos(a1);
  let v = l1 * Math.sin(a1);
  set(out.shoulder, c, s, 0, l0);
  set(out.elbow, c, s, h, l0 + v);
  h += l2 * Math.cos(a2);
  v += l2 * Math.sin(a2);
  set(out.wrist, c, s, h, l0 + v);
  h += l3 * Math.cos(a3);
  v += l3 * Math.sin(a3);
  set(out.tip, c, s, h, l0 + v);
  return out;
}

const scratchPoints = createArmPoints();

/** Tip position and gripper pitch α = θ5 + θ4 + θ3 for these joints. */
export function forwardKinematics(
  j: Joints,
  arm: ArmProfile = DEMO_ARM,
  out: Pose = { x: 0, y: 0, z: 0, alpha: 0 },
): Pose {
  const tip = armPoints(j, arm, scratchPoints).tip;
  out.x = tip.x;
  out.y = tip.y;
  out.z = tip.z;
  out.alpha = j.theta5 + j.theta4 + j.theta3;
  return out;
}

/** Servo angles of 000–003: s = joint − jointOffsetDeg (s001 = θ5 − 90 on the demo arm). */
export function servoAnglesFromJoints(
  j: Joints,
  arm: ArmProfile = DEMO_ARM,
  out: Quad = [0, 0, 0, 0],
): Quad {
  const sv = arm.servos;
  out[0] = j.q0 - (sv[0]?.jointOffsetDeg ?? 0);
  out[1] = j.theta5 - (sv[1]?.jointOffsetDeg ?? 0);
  out[2] = j.theta4 - (sv[2]?.jointOffsetDeg ?? 0);
  out[3] = j.theta3 - (sv[3]?.jointOffsetDeg ?? 0);
  return out;
}

/** Joint angles from the servo angles of 000–003 (the inverse of `servoAnglesFromJoints`). */
export function jointsFromServoAngles(
  s: Readonly<Quad>,
  arm: ArmProfile = DEMO_ARM,
  out: Joints = { q0: 0, theta5: 0, theta4: 0, theta3: 0 },
): Joints {
  const sv = arm.servos;
  out.q0 = s[0] + (sv[0]?.jointOffsetDeg ?? 0);
  out.theta5 = s[1] + (sv[1]?.jointOffsetDeg ?? 0);
  out.theta4 = s[2] + (sv[2]?.jointOffsetDeg ?? 0);
  out.theta3 = s[3] + (sv[3]?.jointOffsetDeg ?? 0);
  return out;
}

const scratchAngles: Quad = [0, 0, 0, 0];

/** Pulse widths (integer µs, §2, with each servo's polarity) of 000–003 for these joints. */
export function pwmFromJoints(
  j: Joints,
  arm: ArmProfile = DEMO_ARM,
  out: Quad = [0, 0, 0, 0],
): Quad {
  const s = servoAnglesFromJoints(j, arm, scratchAngles);
  for (let i = 0; i < 4; i++) out[i] = pwmFromAngle(s[i] ?? NaN, arm.servos[i]?.polarity ?? 1);
  return out;
}
