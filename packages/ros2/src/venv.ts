/**
 * Where the ROS 2 Python lives: the venv `scripts/install-ros2.sh` creates outside the clone, at
 * `${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/ros2-kilted` (the cache root of the
 * other tools), and this package's own Python (`python/armtwin_ros2`), put on PYTHONPATH.
 *
 * Nothing else needs setting: the wheels' `ros_wheels_bootstrapper.pth` re-executes the
 * interpreter once with LD_LIBRARY_PATH on their libraries. ROS_DOMAIN_ID is passed as `--domain`.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** This package's Python: `python -m armtwin_ros2.bridge` runs from here. */
export const ROS2_PYTHON_DIR = path.resolve(
  path.dirname(fileURLToPath(import.meta.url)),
  '..',
  'python',
);

/** The cache root, read the way the install scripts read it (empty counts as unset). */
export function armtwinCacheDir(env: NodeJS.ProcessEnv = process.env): string {
  return (
    env.ARMTWIN_CACHE ||
    path.join(env.XDG_CACHE_HOME || path.join(os.homedir(), '.cache'), 'armtwin')
  );
}

export const ros2VenvDir = (env: NodeJS.ProcessEnv = process.env): string =>
  path.join(armtwinCacheDir(env), 'ros2-kilted');

/** The venv's python; throws a message saying what to run when the venv is not there. */
export function ros2Python(env: NodeJS.ProcessEnv = process.env): string {
  const dir = ros2VenvDir(env);
  const python = path.join(dir, 'bin', 'python');
  if (!fs.existsSync(python))
    throw new Error(
      `ROS 2 is not installed: no venv at ${dir}. Run \`bash scripts/install-ros2.sh\` ` +
        '(or scripts/install-deps.sh): it installs ROS 2 Kilted rclpy and FastDDS from PyPI wheels once per machine',
    );
  return python;
}

/** The environment of a bridge process: this package's Python importable, output unbuffered. */
export function ros2Env(env: NodeJS.ProcessEnv = process.env): NodeJS.ProcessEnv {
  const paths = [ROS2_PYTHON_DIR, env.PYTHONPATH].filter(Boolean).join(path.delimiter);
  return { ...env, PYTHONPATH: paths, PYTHONUNBUFFERED: '1' };
}
