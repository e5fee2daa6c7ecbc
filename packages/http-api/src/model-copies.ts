/**
 * `/api/arms/{id}/model` (docs/protocol.md § Modes): the model copy of arm `{id}`, the
 * simulated arm `{id}-model`, run by a `ModelCopyHost` (`armtwin up`'s; a server without one
 * answers 501).
 *
 * - `POST` (operators; anyone in the anonymous local demo), body `{"pulses": {…}}` or none:
 *   starts the copy (201) or puts the running one at the pose (200):
 *   `{ok, armId, running: true, started, pulses}`.
 * - `GET` (any log-in): `{ok, armId, running}`.
 * - `DELETE` (operators): stops it: `{ok, armId, running: false}`.
 *
 * Refusals as the robot-write routes answer them, `{ok: false, errors}`: 400 for a bad body
 * (every reason), 401/403 for a missing log-in or a viewer's POST/DELETE, 404 for an arm that
 * cannot have a copy, 405 for another method, 413 for a body over `MAX_MODEL_REQUEST_BYTES`,
 * 501 where no host runs copies.
 */
import type http from 'node:http';
import { modelArmId } from '@armtwin/protocol';
import {
  callerMay,
  countedAnswer,
  methodIn,
  type May,
  type RouteCounters,
} from './counted-answer.ts';
import { MAX_MODEL_REQUEST_BYTES, parseModelPose } from './model-pose.ts';
import { readBody } from './read-body.ts';

/**
 * Who runs the model copies: `armtwin up`, whose embedded broker hosts them as in-process
 * simulated arms (apps/up's `ModelCopies`). A server without one answers 501.
 */
export interface ModelCopyHost {
  /** Why arm `armId` cannot have a copy, or '' when it can. */
  refusal(armId: string): string;
  running(armId: string): boolean;
  /** The arm's servo ids (throws when its profile does not load). */
  servoIds(armId: string): number[];
  /** Starts the copy at `pulses` or puts the running one there. */
  start(
    armId: string,
    pulses: ReadonlyMap<number, number>,
  ): Promise<{ started: boolean; pulses: ReadonlyMap<number, number> }>;
  stop(armId: string): Promise<void>;
}

export interface ModelCopyRouteOptions {
  /** null: this server has no simulator to run copies on. */
  copies: ModelCopyHost | null;
  /** Who may start, pose and stop a copy (those who may drive an arm). */
  mayDrive: May;
  /** Who may ask whether a copy runs (any log-in). */
  mayRead: May;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

const NO_HOST =
  'model copies run on `armtwin up` (its embedded broker hosts the simulated copy); this server has none';

export function modelCopyRoute(o: ModelCopyRouteOptions) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('model', counters, o.onFirst);
  const refuse = (res: http.ServerResponse, status: number, errors: string[], kind: string) =>
    answer(res, status, { ok: false, errors }, `refused:${kind}`);

  const handle = async (req: http.IncomingMessage, res: http.ServerResponse, armId: string) => {
    if (!methodIn(req, res, ['GET', 'POST', 'DELETE'])) return;
    const method = req.method ?? '';
    if (!(await callerMay(method === 'GET' ? o.mayRead : o.mayDrive, req, res, answer))) return;
    const copies = o.copies;
    if (!copies) return answer(res, 501, { ok: false, errors: [NO_HOST] }, 'refused:host');
    const why = copies.refusal(armId);
    if (why) return refuse(res, 404, [why], 'arm');
    const copyId = modelArmId(armId);
    if (method === 'GET')
      return answer(res, 200, { ok: true, armId: copyId, running: copies.running(armId) }, 'read');
    if (method === 'DELETE') {
      await copies.stop(armId);
      return answer(res, 200, { ok: true, armId: copyId, running: false }, 'stopped');
    }
    const body = await readBody(req, MAX_MODEL_REQUEST_BYTES);
    if (body === null)
      return refuse(res, 413, [`request over ${MAX_MODEL_REQUEST_BYTES} bytes`], 'size');
    let servoIds: number[];
    try {
      servoIds = copies.servoIds(armId);
    } catch (err) {
      const error = `the profile of arm "${armId}" does not load: ${(err as Error).message}`;
      return answer(res, 500, { ok: false, errors: [error] }, 'failed:profile');
    }
    const pose = parseModelPose(body.toString('utf8'), servoIds);
    if (!pose.ok) return refuse(res, 400, pose.errors, 'pose');
    const r = await copies.start(armId, pose.pulses);
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
