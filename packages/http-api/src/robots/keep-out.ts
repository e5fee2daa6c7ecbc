/**
 * `PUT /api/robots/<name>/keep-out` (an operator's right; anyone in the anonymous local demo):
 * the HUD's Zones section, `{"zones":[…], "linkRadius"?, "selfCollision"?}`, written as the
 * `keepOut` of `<models>/<name>/profile.json` (the first models folder holding it), checked by
 * the profile parser first (`applyKeepOut`: every problem named by zone and field) and written
 * with a backup of the old file (`replaceProfileFile`). The profile file is the one source of
 * truth: the simulator (zones-follow.ts) and the bus gateway (profile-follow.ts) watch it, put
 * the zones in force and announce the profile again, and the pages take them from there.
 *
 * Answers JSON: 200 `{ok, keepOut, backup}`; 400 `{ok:false, errors}`; 401/403 for a missing or
 * non-operator log-in; 404 for an unknown robot; 413 for a body over
 * `MAX_KEEP_OUT_REQUEST_BYTES`.
 */
import type http from 'node:http';
import { applyKeepOut, MAX_KEEP_OUT_REQUEST_BYTES } from '@armtwin/ik';
import { countedAnswer, type RouteCounters } from '../counted-answer.ts';
import { replaceProfileFile } from './profile-file.ts';
import { readProfileFile, readRobotWrite, type RobotWriteOptions } from './robot-write.ts';

export function keepOutRoute(o: RobotWriteOptions) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('keep-out', counters, o.onFirst);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse, name: string) => {
    const write = await readRobotWrite(req, res, o, name, MAX_KEEP_OUT_REQUEST_BYTES, answer);
    if (!write) return;
    const profile = readProfileFile(res, write.file, answer);
    if (!profile) return;
    const applied = applyKeepOut(profile.raw, write.json);
    if (!applied.ok)
      return answer(res, 400, { ok: false, errors: applied.errors }, 'refused:zones');
    const backup = replaceProfileFile(write.file, applied.raw);
    answer(res, 200, { ok: true, keepOut: applied.keepOut, backup }, 'written');
  };
  return { counters, handle };
}
