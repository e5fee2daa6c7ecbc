/**
 * Glue between a chain, its profile and its targets: a target from a 4×4 transform, the chain
 * from a profile and its URDF text in one call, and the pulses of a joint vector.
 */
import { jointFromServo, pwmFromJoint } from '../profile/convert.ts';
import type { Profile } from '../profile/types.ts';
import { buildChain, type BuildChainResult, type Chain } from './chain.ts';
import { DEFAULT_NUMERIC_IK_OPTIONS, type NumericTarget, type TargetMode } from './options.ts';
import { parseUrdfJoints } from './urdf.ts';

/**
 * The target a tip transform `m` (4×4 column-major, mm) describes, in `mode`: its position,
 * rotation (`pose`) or the world direction of `toolAxis` (`axis`).
 */
export function targetFromTransform(
  m: ArrayLike<number>,
  mode: TargetMode,
  toolAxis: readonly [number, number, number] = DEFAULT_NUMERIC_IK_OPTIONS.toolAxis,
): NumericTarget {
  const t: NumericTarget = { mode, x: m[12]!, y: m[13]!, z: m[14]! };
  if (mode === 'pose')
    t.rotation = [m[0]!, m[1]!, m[2]!, m[4]!, m[5]!, m[6]!, m[8]!, m[9]!, m[10]!];
  if (mode === 'axis') {
    const [ax, ay, az] = toolAxis;
    t.axis = [0, 1, 2].map((r) => m[r]! * ax + m[4 + r]! * ay + m[8 + r]! * az);
  }
  return t;
}

/** Parse the URDF text and build the chain `profile.ik` names. */
export function chainFromUrdf(profile: Profile, urdfXml: string): BuildChainResult {
  const urdf = parseUrdfJoints(urdfXml);
  if (!urdf.ok) return { ok: false, errors: urdf.errors.map((e) => `${profile.urdf}: ${e}`) };
  return buildChain(profile, urdf.joints);
}

/**
 * Pulse widths (µs), in `profile.servos` order, for chain joint values `q`; servos not on the
 * chain (a gripper) get NaN (leave them where they are).
 */
export function pwmFromChainJoints(
  profile: Profile,
  chain: Chain,
  q: ArrayLike<number>,
  out: number[] = [],
): number[] {
  out.length = profile.servos.length;
  out.fill(NaN);
  chain.joints.forEach((j, i) => {
    out[j.servoIndex] = pwmFromJoint(profile.servos[j.servoIndex]!, q[i]!);
  });
  return out;
}

/** Chain joint values (radians or metres) of a named pose; joints the pose leaves out get NaN. */
export function chainJointsFromPose(
  profile: Profile,
  chain: Chain,
  pose: string,
): Float64Array | undefined {
  const values = profile.poses[pose];
  if (values === undefined) return undefined;
  return Float64Array.from(chain.joints, (j) =>
    jointFromServo(profile.servos[j.servoIndex]!, values[j.servoIndex] ?? NaN),
  );
}
