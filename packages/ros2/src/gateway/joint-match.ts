/**
 * A ROS 2 arm's JointState matched to an armtwin profile by joint name: where each profile
 * servo's joint is in the message, the profile joints it lacks, and the joints it has that the
 * profile does not drive (a gripper's mimic joint, a mobile base's wheels: ignored). Pure.
 */
import type { Profile } from '@armtwin/robot';

export interface JointMatch {
  /** For each profile servo, its index in the message's `name` (-1: missing). */
  index: number[];
  missing: string[];
  extra: string[];
}

export function matchJoints(profile: Profile, names: readonly string[]): JointMatch {
  const index = profile.servos.map((s) => names.indexOf(s.joint));
  const wanted = new Set(profile.servos.map((s) => s.joint));
  return {
    index,
    missing: profile.servos.filter((_, i) => index[i]! < 0).map((s) => s.joint),
    extra: names.filter((n) => !wanted.has(n)),
  };
}
