/**
 * Sends a calibration to `armtwin up` (`PUT <api>/robots/<name>/calibration`, an operator's
 * right, answered by packages/http-api/src/robots/calibration.ts), with the page's log-in. The server
 * writes the robot's profile.json (keeping a backup); the bus gateway running it takes the new
 * calibration at once and announces it, and the twin follows the announcement.
 */
import type { ServoCalibrationFields } from '@armtwin/robot';
import type { HudSettings } from '../config/settings.ts';
import { putRobotFile } from '../robots/putRobotFile.ts';

export type SaveResult = { ok: true; backup: string } | { ok: false; error: string };

export async function saveCalibration(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  robot: string,
  fields: ServoCalibrationFields,
  fetchFn?: typeof fetch,
): Promise<SaveResult> {
  const r = await putRobotFile(settings, robot, 'calibration', { servos: [fields] }, fetchFn);
  if (!r.ok) return r;
  return typeof r.body.backup === 'string'
    ? { ok: true, backup: r.body.backup }
    : { ok: false, error: 'HTTP 200 without the backup the server keeps' };
}
