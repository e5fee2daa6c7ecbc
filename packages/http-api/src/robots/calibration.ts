/**
 * `PUT /api/robots/<name>/calibration` (an operator's right; anyone in the anonymous local
 * demo): the calibration wizard's result, `{"servos":[{"id","polarity","offset","min","max"}]}`,
 * written into `<models>/<name>/profile.json` (the first models folder holding it). The body is
 * checked (`parseCalibrationRequest`), applied to the profile as it is on disk now
 * (`applyCalibration`, which runs the profile parser on the result) and written with a backup
 * of the old file (`replaceProfileFile`). A bus gateway running that profile watches the file
 * and takes the new calibration at once (docs/arm-side.md).
 *
 * Answers JSON: 200 `{ok, profile, backup}`; 400 `{ok:false, errors}` for a body or result the
 * parser refuses; 401/403 for a missing or non-operator log-in; 404 for an unknown robot; 413
 * for a body over `MAX_CALIBRATION_REQUEST_BYTES`.
 */
import type http from 'node:http';
import {
  applyCalibration,
  MAX_CALIBRATION_REQUEST_BYTES,
  parseCalibrationRequest,
} from '@armtwin/ik';
import { countedAnswer, type RouteCounters } from '../counted-answer.ts';
import { replaceProfileFile } from './profile-file.ts';
import { readProfileFile, readRobotWrite, type RobotWriteOptions } from './robot-write.ts';

export function calibrationRoute(o: RobotWriteOptions) {
  /** Counts by outcome (`written`, `refused:<why>`). */
  const counters: RouteCounters = {};
  const answer = countedAnswer('calibration', counters, o.onFirst);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse, name: string) => {
    const write = await readRobotWrite(req, res, o, name, MAX_CALIBRATION_REQUEST_BYTES, answer);
    if (!write) return;
    const request = parseCalibrationRequest(write.json);
    if (!request.ok)
      return answer(res, 400, { ok: false, errors: request.errors }, 'refused:request');
    const profile = readProfileFile(res, write.file, answer);
    if (!profile) return;
    const applied = applyCalibration(profile.raw, request.servos);
    if (!applied.ok)
      return answer(res, 400, { ok: false, errors: applied.errors }, 'refused:profile');
    const backup = replaceProfileFile(write.file, applied.raw);
    answer(res, 200, { ok: true, profile: applied.raw, backup }, 'written');
  };
  return { counters, handle };
}
