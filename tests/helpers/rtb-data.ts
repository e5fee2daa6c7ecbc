/**
 * Third-party robots as a user gets them: PyPI's `rtb-data` (Robotics Toolbox's robot
 * descriptions) and `example-robot-data` (whose xacro-generated ROS 2 descriptions keep their
 * `<ros2_control>`, `<transmission>` and `<gazebo>` blocks), installed by
 * `scripts/install-deps.sh` into the cached venv beside the servo SDKs. The robots are used as
 * shipped, never edited. Missing is an error, not a skip.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { servoSdkVenv } from './servo-sdk-python.ts';

/** What the venv's python prints for `code`; throws naming `pkg` and what to run. */
function venvPrint(pkg: string, code: string, env: NodeJS.ProcessEnv): string {
  const python = path.join(servoSdkVenv(env), 'bin', 'python');
  const fix = `run \`bash scripts/install-deps.sh\` (it installs ${pkg} into the venv)`;
  if (!fs.existsSync(python)) throw new Error(`no Python venv at ${servoSdkVenv(env)}: ${fix}`);
  try {
    return execFileSync(python, ['-c', code], { stdio: 'pipe' }).toString().trim();
  } catch (err) {
    throw new Error(`${python} has no ${pkg}: ${fix}`, { cause: err });
  }
}

/** The installed `rtbdata` package folder; throws with what to run when it is missing. */
export const rtbDataDir = (env: NodeJS.ProcessEnv = process.env): string =>
  venvPrint('rtb-data', 'import os, rtbdata; print(os.path.dirname(rtbdata.__file__))', env);

/**
 * The installed `example-robot-data` folder (a cmeel wheel: data under `cmeel.prefix/share` in
 * the venv's site-packages, no Python module); throws with what to run when it is missing.
 */
export const exampleRobotDataDir = (env: NodeJS.ProcessEnv = process.env): string =>
  venvPrint(
    'example-robot-data',
    'import os, sysconfig; d = os.path.join(sysconfig.get_paths()["purelib"], ' +
      '"cmeel.prefix", "share", "example-robot-data"); ' +
      'assert os.path.isdir(os.path.join(d, "robots")), d; print(d)',
    env,
  );

/** The ROS 2 robots the import tests use, as paths inside `example-robot-data`. */
export const ROS2_ROBOTS = {
  /** UFACTORY xArm7: 7 axes, `<ros2_control>`, 7 `<transmission>`s, `<gazebo>`s, STL meshes. */
  xarm7: 'robots/xarm_description/urdf/xarm7.urdf',
} as const;

/** The robots the import tests use, as paths inside `rtbdata`. */
export const RTB_ROBOTS = {
  /** KUKA LBR iiwa 14 R820: 7 axes, `package://` paths, DAE visuals and STL collisions. */
  iiwa14: 'xacro/kuka_description/kuka_lbr_iiwa/urdf/lbr_iiwa_14_r820.urdf',
  /** ABB IRB 140: 6 axes, `package://` paths, STL meshes, joints beyond 270°. */
  irb140: 'xacro/abb_irb140_description/urdf/irb140.urdf',
} as const;
