/**
 * `/api/arms/{id}/model` (docs/protocol.md § Modes): the model copy of arm `{id}`, the
 * simulated arm `{id}-model` (./model-copies.ts).
 *
 * - `POST` (operators; anyone in the anonymous local demo), body `{"pulses": {…}}` or none:
 *   starts the copy (201) or puts the running one at the pose (200):
 *   `{ok, armId, running: true, started, pulses}`.
 * - `GET` (any log-in): `{ok, armId, running}`.
 * - `DELETE` (operators): stops it: `{ok, armId, running: false}`.
 *
 * Refusals as the robot-write routes answer them, `{ok: false, errors}`: 400 for a bad body
 * (every reason), 401/403 for a missing log-in or a viewer's POST/DELETE, 404 for an arm that
 * cannot have a copy, 405 for another method, 413 for a body over `MAX_MODEL_REQUEST_BYTES`.
 */
import type http from 'node:http';
import { modelArmId } from '@armtwin/protocol';
import type { Authorize } from './calibration-route.ts';
import { countedAnswer, type RouteCounters } from './counted-answer.ts';
import type { ModelCopies } from './model-copies.ts';
import { MAX_MODEL_REQUEST_BYTES, parseModelPose } from './model-pose.ts';
import { readBody } from './read-body.ts';

const ROUTE = /^\/api\/arms\/([^/?]+)\/model(?:\?.*)?$/;
const METHODS = 'GET, POST, DELETE';

export interface ModelCopyRouteOptions {
  copies: ModelCopies;
  /** Who may start, pose and stop a copy (those who may drive an arm). */
  mayDrive: Authorize;
  /** Who may ask whether a copy runs (any log-in). */
  mayRead: Authorize;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

export const isModelCopyRequest = (req: http.IncomingMessage): boolean => ROUTE.test(req.url ?? '');

export function modelCopyRoute(o: ModelCopyRouteOptions) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('model', counters, o.onFirst);
  const refuse = (res: http.ServerResponse, status: number, errors: string[], kind: string) =>
    answer(res, status, { ok: false, errors }, `refused:${kind}`);

  const handle = async (req: http.IncomingMessage, res: http.ServerResponse) => {
    const method = req.method ?? '';
    if (!['GET', 'POST', 'DELETE'].includes(method)) {
      res.writeHead(405, { allow: METHODS }).end();
      return;
    }
    const who = await (method === 'GET' ? o.mayRead : o.mayDrive)(req);
    if (!who.ok) return refuse(res, who.status, [who.error], 'role');
    const armId = decodeId(ROUTE.exec(req.url ?? '')![1]!);
    const why = o.copies.refusal(armId);
    if (why) return refuse(res, 404, [why], 'arm');
    const copyId = modelArmId(armId);
    if (method === 'GET')
      return answer(
        res,
        200,
        { ok: true, armId: copyId, running: o.copies.running(armId) },
        'read',
      );
    if (method === 'DELETE') {
      await o.copies.stop(armId);
      return answer(res, 200, { ok: true, armId: copyId, running: false }, 'stopped');
    }
    const body = await readBody(req, MAX_MODEL_REQUEST_BYTES);
    if (body === null)
      return refuse(res, 413, [`request over ${MAX_MODEL_REQUEST_BYTES} bytes`], 'size');
    let servoIds: number[];
    try {
      servoIds = o.copies.servoIds(armId);
    } catch (err) {
      const error = `the profile of arm "${armId}" does not load: ${(err as Error).message}`;
      return answer(res, 500, { ok: false, errors: [error] }, 'failed:profile');
    }
    const pose = parseModelPose(body.toString('utf8'), servoIds);
    if (!pose.ok) return refuse(res, 400, pose.errors, 'pose');
    const r = await o.copies.start(armId, pose.pulses);
    answer(
      res,
      r.started ? 201 : 200,
      {
        ok: true,
        armId: copyId,
        running: true,
        started: r.started,
        pulses: Object.fromEntries(r.pulses),
      },
      r.started ? 'started' : 'posed',
    );
  };
  return { counters, handle };
}

/** The `{id}` of the path ('' for a malformed escape: no arm has that id). */
function decodeId(raw: string): string {
  try {
    return decodeURIComponent(raw);
  } catch {
    return '';
  }
}
