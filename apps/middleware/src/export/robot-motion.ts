/**
 * The arm's motion in a recording as a robot tool shows it: the profile servos' URDF joint
 * values at each recorded instant (a `JointStates` sample), and every URDF joint's transform from
 * its parent link to its child link at those values (Foxglove's `FrameTransform`), so a 3D panel
 * draws the arm moving. Joint values follow the profile (`jointFromPwm`, or `jointFromServo` for
 * a bus servo's angle, PROTOCOL.md §8); URDF joints the profile does not drive stay at 0, a mimic
 * joint takes its master's value. Transforms use @armtwin/ik's URDF math. Pure.
 */
import {
  createMat4,
  mat4FromXyzRpy,
  mat4RotateAxisInPlace,
  mat4TranslateAxisInPlace,
  type Mat4,
} from '@armtwin/ik';
import { jointFromPwm, jointFromServo, type Profile, type UrdfJoint } from '@armtwin/robot';
import type { ServoRow } from './recording.ts';

export interface JointSample {
  ns: bigint;
  /** URDF joint names of the profile's servos, in servo order. */
  names: readonly string[];
  /** Their values (rad, or m for a prismatic joint); NaN until the servo's first report. */
  positions: number[];
}

export interface LinkTransform {
  parent: string;
  child: string;
  translation: [number, number, number];
  /** Unit quaternion x, y, z, w. */
  rotation: [number, number, number, number];
}

/** The joint value a stored point gives servo `s`, or undefined if it holds no position. */
function jointValue(s: Profile['servos'][number], row: ServoRow): number | undefined {
  if (row.pwm !== undefined) return jointFromPwm(s, row.pwm);
  if (row.angle !== undefined) return jointFromServo(s, row.angle);
  return undefined;
}

/**
 * One sample per instant at which a profile servo reported a position (rows in time order); each
 * holds every servo's latest value, so a group's servos land in one sample.
 */
export function jointSamples(profile: Profile, rows: readonly ServoRow[]): JointSample[] {
  const index = new Map(profile.servos.map((s, i) => [s.id, i]));
  const names = profile.servos.map((s) => s.joint);
  const current = profile.servos.map(() => NaN);
  const out: JointSample[] = [];
  let open: bigint | null = null;
  const close = () => {
    if (open !== null) out.push({ ns: open, names, positions: [...current] });
    open = null;
  };
  for (const row of rows) {
    const i = index.get(Number(row.id));
    if (i === undefined) continue;
    const q = jointValue(profile.servos[i]!, row);
    if (q === undefined) continue;
    if (open !== null && row.ns !== open) close();
    current[i] = q;
    open = row.ns;
  }
  close();
  return out;
}

/**
 * The joints as commanded, one sample per command instant (`targets`: `jointSamples` of the
 * command rows), every joint filled: a servo not commanded yet in the range holds where it
 * stands, so it takes its latest reported value (`reported`: `jointSamples` of the servo rows).
 * Every sample then lists the same joints in the same order as the joint states.
 */
export function targetSamples(
  targets: readonly JointSample[],
  reported: readonly JointSample[],
): JointSample[] {
  let r = -1;
  return targets.map((t) => {
    while (r + 1 < reported.length && reported[r + 1]!.ns <= t.ns) r++;
    const stands = reported[r]?.positions;
    return {
      ...t,
      positions: t.positions.map((q, i) => (Number.isNaN(q) ? (stands?.[i] ?? NaN) : q)),
    };
  });
}

/** Rotation of a rigid transform as a unit quaternion (x, y, z, w). */
function quaternionOf(m: Mat4): [number, number, number, number] {
  const [m00, m10, m20, , m01, m11, m21, , m02, m12, m22] = m as unknown as number[];
  const trace = m00! + m11! + m22!;
  let x: number, y: number, z: number, w: number;
  if (trace > 0) {
    const s = 0.5 / Math.sqrt(trace + 1);
    w = 0.25 / s;
    x = (m21! - m12!) * s;
    y = (m02! - m20!) * s;
    z = (m10! - m01!) * s;
  } else if (m00! > m11! && m00! > m22!) {
    const s = 2 * Math.sqrt(1 + m00! - m11! - m22!);
    w = (m21! - m12!) / s;
    x = 0.25 * s;
    y = (m01! + m10!) / s;
    z = (m02! + m20!) / s;
  } else if (m11! > m22!) {
    const s = 2 * Math.sqrt(1 + m11! - m00! - m22!);
    w = (m02! - m20!) / s;
    x = (m01! + m10!) / s;
    y = 0.25 * s;
    z = (m12! + m21!) / s;
  } else {
    const s = 2 * Math.sqrt(1 + m22! - m00! - m11!);
    w = (m10! - m01!) / s;
    x = (m02! + m20!) / s;
    y = (m12! + m21!) / s;
    z = 0.25 * s;
  }
  const n = Math.hypot(x, y, z, w);
  return [x / n, y / n, z / n, w / n];
}

/** Every URDF joint's parent → child transform at `values` (joint name → rad or m). */
export function linkTransforms(
  joints: readonly UrdfJoint[],
  values: ReadonlyMap<string, number>,
): LinkTransform[] {
  const m = createMat4();
  return joints.map((j) => {
    const q = values.get(j.mimic ?? j.name) ?? values.get(j.name) ?? 0;
    mat4FromXyzRpy(m, ...j.xyz, ...j.rpy);
    const [ax, ay, az] = j.axis;
    const n = Math.hypot(ax, ay, az) || 1;
    if (j.type === 'revolute' || j.type === 'continuous')
      mat4RotateAxisInPlace(m, ax / n, ay / n, az / n, Number.isFinite(q) ? q : 0);
    else if (j.type === 'prismatic')
      mat4TranslateAxisInPlace(m, ax / n, ay / n, az / n, Number.isFinite(q) ? q : 0);
    return {
      parent: j.parent,
      child: j.child,
      translation: [m[12]!, m[13]!, m[14]!],
      rotation: quaternionOf(m),
    };
  });
}
