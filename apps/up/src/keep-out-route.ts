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
import fs from 'node:fs';
import type http from 'node:http';
import path from 'node:path';
import { applyKeepOut, MAX_KEEP_OUT_REQUEST_BYTES } from '@armtwin/ik';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import type { Authorize } from './calibration-route.ts';
import { countedAnswer, type RouteCounters } from './counted-answer.ts';
import { replaceProfileFile } from './profile-file.ts';
import { readBody } from './read-body.ts';

const ROUTE = /^\/api\/robots\/([^/?]+)\/keep-out(?:\?.*)?$/;

export interface KeepOutRouteOptions {
  /** Models folders, searched in order. */
  dirs: readonly string[];
  authorize: Authorize;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

export const isKeepOutRequest = (req: http.IncomingMessage): boolean => ROUTE.test(req.url ?? '');

export function keepOutRoute(o: KeepOutRouteOptions) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('keep-out', counters, o.onFirst);
  const handle = async (req: http.IncomingMessage, res: http.ServerResponse) => {
    if (req.method !== 'PUT') {
      res.writeHead(405, { allow: 'PUT' }).end();
      return;
    }
    const name = decodeURIComponent(ROUTE.exec(req.url ?? '')![1]!);
    const who = await o.authorize(req);
    if (!who.ok) return answer(res, who.status, { ok: false, errors: [who.error] }, 'refused:role');
    const file = PROFILE_NAME.test(name)
      ? o.dirs.map((d) => path.join(d, name, 'profile.json')).find((f) => fs.existsSync(f))
      : undefined;
    if (!file)
      return answer(res, 404, { ok: false, errors: [`no robot "${name}"`] }, 'refused:robot');
    const body = await readBody(req, MAX_KEEP_OUT_REQUEST_BYTES);
    if (body === null)
      return answer(
        res,
        413,
        { ok: false, errors: [`request over ${MAX_KEEP_OUT_REQUEST_BYTES} bytes`] },
        'refused:size',
      );
    let json: unknown;
    let raw: unknown;
    try {
      json = JSON.parse(body.toString('utf8'));
    } catch {
      return answer(res, 400, { ok: false, errors: ['the request is not JSON'] }, 'refused:json');
    }
    try {
      raw = JSON.parse(fs.readFileSync(file, 'utf8'));
    } catch (err) {
      const error = `${file} does not read: ${(err as Error).message}`;
      return answer(res, 500, { ok: false, errors: [error] }, 'failed:read');
    }
    const applied = applyKeepOut(raw, json);
    if (!applied.ok)
      return answer(res, 400, { ok: false, errors: applied.errors }, 'refused:zones');
    const backup = replaceProfileFile(file, applied.raw);
    answer(res, 200, { ok: true, keepOut: applied.keepOut, backup }, 'written');
  };
  return { counters, handle };
}
