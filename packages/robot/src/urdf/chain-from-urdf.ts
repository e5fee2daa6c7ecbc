/**
 * Glue between a chain and its profile: the chain from a profile and its URDF text in one call,
 * the pulses of a joint vector, and the joint values of a named pose.
 */
import type { Chain } from '@armtwin/ik';
import { jointFromServo, pwmFromJoint } from '../profile/convert.ts';
import type { Profile } from '../profile/types.ts';
import { buildChain, type BuildChainResult } from './build-chain.ts';
import { parseUrdfJoints } from './urdf.ts';

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
