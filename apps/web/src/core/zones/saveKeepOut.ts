/**
 * Sends a robot's keep-out zones to `armtwin up` (`PUT <api>/robots/<name>/keep-out`, an
 * operator's right, answered by packages/http-api/src/robots/keep-out.ts), with the page's log-in. The
 * server checks them (every problem named by zone and field) and writes them into the robot's
 * profile.json; the simulator and the bus gateway take them from the file at once and announce
 * the profile again, and this page draws and checks them from that announcement.
 */
import type { ProfileKeepOut } from '@armtwin/robot';
import type { HudSettings } from '../config/settings.ts';
import { putRobotFile } from '../robots/putRobotFile.ts';

export type SaveKeepOutResult = { ok: true } | { ok: false; error: string };

export async function saveKeepOut(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  robot: string,
  keepOut: ProfileKeepOut,
  fetchFn?: typeof fetch,
): Promise<SaveKeepOutResult> {
  const r = await putRobotFile(settings, robot, 'keep-out', keepOut, fetchFn);
  return r.ok ? { ok: true } : r;
}
