/**
 * A simulated SO-101 follower with a keep-out zone, for the LeRobot and leader-arm tests: the
 * shipped so101 folder copied under `modelsDir` with `ZONE` added, and `armtwin sim` of it on
 * the broker, reporting angles at 50 Hz.
 */
import fs from 'node:fs';
import path from 'node:path';
import { MODELS_DIR } from '@armtwin/sim';
import { armtwin, type Child } from './sim-helpers.ts';

/** Where the SO-101's gripper frame sweeps with shoulder_pan past about +30° (others at 0). */
export const ZONE = { name: 'bin', shape: 'box', min: [250, -280, 150], max: [360, -190, 300] };

export function startSo101Follower(brokerUrl: string, arm: string, modelsDir: string): Child {
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS_DIR, 'so101', 'profile.json'), 'utf8'),
  ) as Record<string, unknown>;
  fs.cpSync(path.join(MODELS_DIR, 'so101'), path.join(modelsDir, 'so101'), { recursive: true });
  fs.writeFileSync(
    path.join(modelsDir, 'so101', 'profile.json'),
    JSON.stringify({ ...raw, keepOut: { zones: [ZONE] } }),
  );
  return armtwin([
    'sim',
    ...['--mqtt', brokerUrl, '--arm', arm, '--profile', 'so101', '--models', modelsDir],
    ...['--report', 'angle', '--rate', '50'],
  ]);
}
