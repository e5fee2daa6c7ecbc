/**
 * `armtwin sim --profile <name>`: the robot profile `public/models/<name>/profile.json` (and, for
 * a numeric one, its URDF), turned into what the simulator runs: the servo table (ids, pulse
 * limits, speeds, home), a `$KMS` solver for arms the §4 solver does not describe, the planner's
 * robot for motion requests, and the retained announcement for `arm/{id}/profile`.
 *
 * The servo model (servos.ts) counts in degrees of a §2 servo. An `analytic5` profile gives it
 * its own `ArmProfile` (armtwin5's equals DEMO_ARM, so the default sim behaves exactly as
 * before). Any other profile gets a pulse-equivalent one: each servo's pulse limits and pulse
 * speed from `servoTable(profile)`, written as §2 angles with polarity +1, which round-trip to
 * exactly the same pulses (a prismatic axis included).
 */
import {
  armProfileFromProfile,
  chainFromUrdf,
  MAX_PROFILE_ANNOUNCEMENT_BYTES,
  profileAnnouncement,
  pulseEquivalentArm,
  type Profile,
} from '@armtwin/robot';
import { numericKms, zonesKeepOut } from '@armtwin/controller';
import { createMotionRobot, type MotionRobot } from '@armtwin/motion';
import { MODELS_DIR, PROFILE_NAME, readRobotFolder } from '@armtwin/motion/robot-folder';
import { PWM_CENTRE } from '@armtwin/protocol';
import type { SimModelOptions } from './options.ts';

export { MODELS_DIR, PROFILE_NAME };
export const DEFAULT_PROFILE = 'armtwin5';

export interface SimProfile {
  profile: Profile;
  /** The planner's robot (motion requests). */
  robot: MotionRobot;
  /** What the servo model needs: the arm, the pulses at power-on, and `$KMS` for numeric arms. */
  model: Partial<SimModelOptions>;
  /** The retained payload of `arm/{id}/profile`: `{"name", "title", "profile": <profile.json>}`. */
  announcement: string;
}

/** The `$KMS` solver and keep-out checks of a profile, declared once in @armtwin/controller. */
export { floorKeepOut, numericKms, zonesKeepOut } from '@armtwin/controller';

/** Builds the sim's view of a parsed profile; `urdf` is needed for a numeric one. */
export function simProfile(profile: Profile, raw: unknown, urdf?: string): SimProfile {
  let chain;
  if (profile.ik.kind === 'numeric') {
    if (urdf === undefined) throw new Error(`profile ${profile.name}: its URDF is needed`);
    const built = chainFromUrdf(profile, urdf);
    if (!built.ok) throw new Error(`profile ${profile.name}: ${built.errors.join('; ')}`);
    chain = built.chain;
  }
  const robot = createMotionRobot(profile, chain);
  const analytic = profile.ik.kind === 'analytic5' ? armProfileFromProfile(profile) : undefined;
  const model: Partial<SimModelOptions> = {
    arm: analytic ?? pulseEquivalentArm(profile),
    initialPwm: robot.table.map((s) => (Number.isFinite(s.homePwm) ? s.homePwm : PWM_CENTRE)),
    keepOut: zonesKeepOut(robot),
  };
  if (!analytic) model.kms = numericKms(robot);
  const announcement = profileAnnouncement(profile.name, profile.title, raw);
  if (Buffer.byteLength(announcement) > MAX_PROFILE_ANNOUNCEMENT_BYTES)
    throw new Error(
      `profile ${profile.name}: ${Buffer.byteLength(announcement)} bytes is too large to announce (at most ${MAX_PROFILE_ANNOUNCEMENT_BYTES})`,
    );
  return { profile, robot, model, announcement };
}

/** Reads `<modelsDir>/<name>/profile.json` (and its URDF); throws with every problem found. */
export function loadSimProfile(name: string, modelsDir = MODELS_DIR): SimProfile {
  const { profile, raw, urdf } = readRobotFolder(name, modelsDir);
  return simProfile(profile, raw, urdf);
}
