/**
 * Third-party robots as a user gets them: PyPI's `rtb-data` (Robotics Toolbox's robot
 * descriptions), installed by `scripts/install-deps.sh` into the cached venv beside the servo
 * SDKs. The robots are used as shipped, never edited. Missing is an error, not a skip.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { servoSdkVenv } from './servo-sdk-python.ts';

/** The installed `rtbdata` package folder; throws with what to run when it is missing. */
export function rtbDataDir(env: NodeJS.ProcessEnv = process.env): string {
  const python = path.join(servoSdkVenv(env), 'bin', 'python');
  const fix = 'run `bash scripts/install-deps.sh` (it installs rtb-data into the venv)';
  if (!fs.existsSync(python)) throw new Error(`no Python venv at ${servoSdkVenv(env)}: ${fix}`);
  try {
    return execFileSync(
      python,
      ['-c', 'import os, rtbdata; print(os.path.dirname(rtbdata.__file__))'],
      { stdio: 'pipe' },
    )
      .toString()
      .trim();
  } catch (err) {
    throw new Error(`${python} cannot import rtbdata: ${fix}`, { cause: err });
  }
}

/** The robots the import tests use, as paths inside `rtbdata`. */
export const RTB_ROBOTS = {
  /** KUKA LBR iiwa 14 R820: 7 axes, `package://` paths, DAE visuals and STL collisions. */
  iiwa14: 'xacro/kuka_description/kuka_lbr_iiwa/urdf/lbr_iiwa_14_r820.urdf',
  /** ABB IRB 140: 6 axes, `package://` paths, STL meshes, joints beyond 270°. */
  irb140: 'xacro/abb_irb140_description/urdf/irb140.urdf',
} as const;
