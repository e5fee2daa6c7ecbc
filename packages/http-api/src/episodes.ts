/**
 * `/arms/{id}/episodes`: an arm's episodes, marked time ranges of its history with a task
 * (docs/dataset.md). `GET` (`?from=&to=`, ISO times; anyone who may read the history) lists
 * them; `POST {"action":"start","task":"…"}`, `{"action":"stop"}`, `{"action":"discard"}`
 * (`"start"`: a stopped one), or `{"action":"cut","task":"…","from":…,"to":…}` (an operator's
 * right; anyone in the anonymous local demo) marks one, under the caller's name (`by`). The
 * middleware keeps them (`ApiService.episodes`); without storage the route answers 503.
 */
import type http from 'node:http';
import { isValidArmId } from '@armtwin/protocol';
import {
  callerMay,
  countedAnswer,
  methodIn,
  type May,
  type RouteCounters,
} from './counted-answer.ts';
import { readBody } from './read-body.ts';
import type { ApiService } from './service-routes.ts';
import { TIME_RANGE_ERROR, timeRange } from './time-range.ts';

export const MAX_EPISODE_REQUEST_BYTES = 4096;

export interface EpisodeAnswer {
  status: number;
  body: unknown;
}

/** What the middleware lends the route. */
export interface EpisodeService {
  list(arm: string, fromMs?: number, toMs?: number): Promise<unknown[]>;
  /** `by`: who asks (a user's name, `token` or `anonymous`). */
  act(arm: string, body: unknown, by?: string): Promise<EpisodeAnswer>;
}

export function episodesRoute(o: {
  service: () => ApiService | null;
  mayRead: May;
  mayMark: May;
  /** The name an episode is marked under (after `mayMark` let the caller in). */
  callerName(req: http.IncomingMessage): Promise<string>;
  onFirst(kind: string, message: string): void;
}) {
  const counters: RouteCounters = {};
  const answer = countedAnswer('episodes', counters, o.onFirst);
  return {
    counters,
    async handle(req: http.IncomingMessage, res: http.ServerResponse, arm: string) {
      if (!methodIn(req, res, ['GET', 'POST'])) return;
      const reading = req.method === 'GET';
      if (!(await callerMay(reading ? o.mayRead : o.mayMark, req, res, answer))) return;
      if (!isValidArmId(arm))
        return answer(res, 400, { ok: false, errors: [`not an arm id: ${arm}`] }, 'refused:arm');
      const episodes = o.service()?.episodes;
      if (!episodes)
        return answer(
          res,
          503,
          { ok: false, errors: ['episodes need storage: set INFLUX_URL'] },
          'failed:storage',
        );
      if (reading) {
        const range = timeRange(req);
        if (!range)
          return answer(res, 400, { ok: false, errors: [TIME_RANGE_ERROR] }, 'refused:request');
        return answer(
          res,
          200,
          { ok: true, episodes: await episodes.list(arm, range.from, range.to) },
          'listed',
        );
      }
      const raw = await readBody(req, MAX_EPISODE_REQUEST_BYTES);
      if (!raw)
        return answer(
          res,
          413,
          { ok: false, errors: [`body over ${MAX_EPISODE_REQUEST_BYTES} bytes`] },
          'refused:size',
        );
      let json: unknown;
      try {
        json = JSON.parse(raw.toString('utf8'));
      } catch {
        return answer(res, 400, { ok: false, errors: ['the body is not JSON'] }, 'refused:request');
      }
      const r = await episodes.act(arm, json, await o.callerName(req));
      const kind =
        r.status < 300 ? 'marked' : r.status === 409 ? 'refused:state' : 'refused:request';
      return answer(res, r.status, r.body, kind);
    },
  };
}
