/**
 * A robot's folder on disk (`<models>/<name>/profile.json`, and the URDF a numeric profile's
 * IK needs), read once here for the simulator and the bus gateway. Node only: imported as
 * `@armtwin/motion/robot-folder`, so the package's main entry stays free of I/O.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chainFromUrdf, parseProfile, type Profile } from '@armtwin/robot';
import { createMotionRobot, type MotionRobot } from './robot.ts';

/** The robots' folders shipped with armtwin: `public/models` at the repository root. */
export const MODELS_DIR = path.resolve(
  path.dirname(fileURLToPath(import.meta.url)),
  '..',
  '..',
  '..',
  'public',
  'models',
);
/** A profile name is a folder name: `[a-z0-9_-]{1,32}` (so it can never leave its models dir). */
export const PROFILE_NAME = /^[a-z0-9_-]{1,32}$/;

export interface RobotFolder {
  profile: Profile;
  /** profile.json as it was read (what the arm announces). */
  raw: unknown;
  /** The URDF's text, for a numeric profile. */
  urdf: string | undefined;
  /** The planner's robot. */
  robot: MotionRobot;
}

/** Reads and checks `<modelsDir>/<name>/`; throws a message naming what is wrong. */
export function readRobotFolder(name: string, modelsDir = MODELS_DIR): RobotFolder {
  if (!PROFILE_NAME.test(name)) throw new Error(`profile name must match ${PROFILE_NAME.source}`);
  const dir = path.join(modelsDir, name);
  const file = path.join(dir, 'profile.json');
  if (!fs.existsSync(file)) {
    const have = fs.existsSync(modelsDir)
      ? fs
          .readdirSync(modelsDir)
          .filter((d) => fs.existsSync(path.join(modelsDir, d, 'profile.json')))
      : [];
    throw new Error(
      `no profile "${name}" (${file} is missing; profiles: ${have.join(', ') || 'none'})`,
    );
  }
  const raw: unknown = JSON.parse(fs.readFileSync(file, 'utf8'));
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(`${file}:\n  ${parsed.errors.join('\n  ')}`);
  const { profile } = parsed;
  if (profile.ik.kind !== 'numeric')
    return { profile, raw, urdf: undefined, robot: createMotionRobot(profile) };
  const urdf = fs.readFileSync(path.join(dir, profile.urdf), 'utf8');
  const built = chainFromUrdf(profile, urdf);
  if (!built.ok) throw new Error(`profile ${name}: ${built.errors.join('; ')}`);
  return { profile, raw, urdf, robot: createMotionRobot(profile, built.chain) };
}
