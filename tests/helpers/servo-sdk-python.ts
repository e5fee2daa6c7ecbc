/**
 * The Python that has the vendors' servo SDKs (ROBOTIS `dynamixel-sdk`, Feetech
 * `feetech-servo-sdk`): the venv `scripts/install-deps.sh` creates outside the clone, at
 * `${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/pyenv` (the same cache root as
 * influxd). Missing is an error, not a skip: the SDK test is how the emulation is proved.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { armtwinCacheDir } from '@armtwin/ros2';

export const servoSdkVenv = (env: NodeJS.ProcessEnv = process.env): string =>
  path.join(armtwinCacheDir(env), 'pyenv');

/** The venv's python, checked to import both SDKs; throws with what to run when it cannot. */
export function servoSdkPython(env: NodeJS.ProcessEnv = process.env): string {
  const python = path.join(servoSdkVenv(env), 'bin', 'python');
  const fix =
    'run `bash scripts/install-deps.sh` (it creates the venv with dynamixel-sdk and feetech-servo-sdk)';
  if (!fs.existsSync(python))
    throw new Error(
      `no Python venv for the servo SDKs at ${path.dirname(path.dirname(python))}: ${fix}`,
    );
  try {
    execFileSync(python, ['-c', 'import dynamixel_sdk, scservo_sdk, serial'], { stdio: 'pipe' });
  } catch (err) {
    const detail =
      (err as { stderr?: Buffer }).stderr?.toString().trim().split('\n').at(-1) ?? String(err);
    throw new Error(`${python} cannot import the servo SDKs (${detail}): ${fix}`, { cause: err });
  }
  return python;
}
