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
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import {
  applyCalibration,
  MAX_CALIBRATION_REQUEST_BYTES,
  parseCalibrationRequest,
} from '@armtwin/ik';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import { countedAnswer } from './counted-answer.ts';
import { replaceProfileFile } from './profile-file.ts';
import { readBody } from './read-body.ts';

const ROUTE = /^\/api\/robots\/([^/?]+)\/calibration(?:\?.*)?$/;

/** Who may write: `ok`, or the status and reason to refuse with. */
export type Authorize = (
  req: http.IncomingMessage,
) => Promise<{ ok: true } | { ok: false; status: 401 | 403; error: string }>;

export interface CalibrationRouteOptions {
  /** Models folders, searched in order. */
  dirs: readonly string[];
  authorize: Authorize;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

export const isCalibrationRequest = (req: http.IncomingMessage): boolean =>
  ROUTE.test(req.url ?? '');

/** Counts by outcome (`written`, `refused:<why>`). */
export type CalibrationCounters = Record<string, number>;

export function calibrationRoute(o: CalibrationRouteOptions) {
  const counters: CalibrationCounters = {};
  const answer = countedAnswer('calibration', counters, o.onFirst);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse) => {
    if (req.method !== 'PUT') {
      res.writeHead(405, { allow: 'PUT' }).end();
      return;
    }
    const name = decodeURIComponent(ROUTE.exec(req.url ?? '')![1]!);
    const who = await o.authorize(req);
    if (!who.ok) return answer(res, who.status, { ok: false, errors: [who.error] }, 'refused:role');
    if (!PROFILE_NAME.test(name))
      return answer(res, 404, { ok: false, errors: [`no robot "${name}"`] }, 'refused:robot');
    const file = o.dirs
      .map((d) => path.join(d, name, 'profile.json'))
      .find((f) => fs.existsSync(f));
    if (!file)
      return answer(res, 404, { ok: false, errors: [`no robot "${name}"`] }, 'refused:robot');
    const body = await readBody(req, MAX_CALIBRATION_REQUEST_BYTES);
    if (body === null)
      return answer(
        res,
        413,
        { ok: false, errors: [`request over ${MAX_CALIBRATION_REQUEST_BYTES} bytes`] },
        'refused:size',
      );
    let json: unknown;
    try {
      json = JSON.parse(body.toString('utf8'));
    } catch {
      return answer(res, 400, { ok: false, errors: ['the request is not JSON'] }, 'refused:json');
    }
    const request = parseCalibrationRequest(json);
    if (!request.ok)
      return answer(res, 400, { ok: false, errors: request.errors }, 'refused:request');
    let raw: unknown;
    try {
      raw = JSON.parse(fs.readFileSync(file, 'utf8'));
    } catch (err) {
      const error = `${file} does not read: ${(err as Error).message}`;
      return answer(res, 500, { ok: false, errors: [error] }, 'failed:read');
    }
    const applied = applyCalibration(raw, request.servos);
    if (!applied.ok)
      return answer(res, 400, { ok: false, errors: applied.errors }, 'refused:profile');
    const backup = replaceProfileFile(file, applied.raw);
    answer(res, 200, { ok: true, profile: applied.raw, backup }, 'written');
  };
  return { counters, handle };
}
