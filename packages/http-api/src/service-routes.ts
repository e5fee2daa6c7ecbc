/**
 * The middleware's routes: `/healthz` (JSON, 200 or 503, always open), `/metrics` (Prometheus
 * text) and `/history/…` (the history API, present when the middleware has storage), both
 * `data` (./authorize.ts); and `/whoami`, which tells the HUD its role. Under `armtwin up` the
 * middleware starts after the server: until it runs these answer 503 and say so.
 */
import type http from 'node:http';
import { whoamiAnswer } from '@armtwin/auth';
import { refusal, type AuthOptions, type Authorize } from './authorize.ts';
import type { CameraSegmentService } from './camera-segments.ts';
import type { EpisodeService } from './episodes.ts';
import { sendJson } from './send-json.ts';

/** What the middleware lends the API. */
export interface ApiService {
  /** The health report; `ok` decides 200 or 503. Also refreshes the metrics' gauges. */
  health(): { ok: boolean };
  /** The metrics in Prometheus text format. */
  metrics(): string | Promise<string>;
  /**
   * The history API for a request whose URL starts `/history` (true once answered, false for
   * a path it does not know), or null when there is no storage to read from.
   */
  history: ((req: http.IncomingMessage, res: http.ServerResponse) => Promise<boolean>) | null;
  /** An arm's episode marks (./episodes.ts), or null/absent when there is no storage. */
  episodes?: EpisodeService | null;
  /** The cameras' recorded segments (./camera-segments.ts), or null/absent when not recording. */
  cameras?: CameraSegmentService | null;
}

const MIDDLEWARE_MISSING = { ok: false, storage: false, error: 'the middleware is not running' };
const READ_METHODS = ['GET', 'HEAD'];

export function serviceRoutes(o: {
  auth: AuthOptions;
  authorize: Authorize;
  service: () => ApiService | null;
}) {
  /** Serves `serve` once the caller may read the data; else 401/429 as the middleware always has. */
  const gated = async (
    req: http.IncomingMessage,
    res: http.ServerResponse,
    serve: (s: ApiService) => Promise<void> | void,
  ) => {
    const why = refusal(o.auth, req, await o.authorize(req), 'data');
    if (why) {
      // Never a Basic challenge: a browser would open its own log-in dialog over the HUD (whose
      // requests carry the page's log-in themselves); the body says what to send.
      const headers: Record<string, string> =
        why.status === 429
          ? { 'retry-after': String(why.retryAfterS) }
          : { 'www-authenticate': 'Bearer realm="armtwin"' };
      return sendJson(res, why.status, { error: why.error }, headers);
    }
    const s = o.service();
    if (!s) return sendJson(res, 503, MIDDLEWARE_MISSING);
    await serve(s);
  };
  const readOnly = (req: http.IncomingMessage, res: http.ServerResponse) => {
    if (READ_METHODS.includes(req.method ?? '')) return true;
    res.writeHead(405, { allow: 'GET, HEAD' }).end();
    return false;
  };

  return {
    healthz(req: http.IncomingMessage, res: http.ServerResponse) {
      if (!readOnly(req, res)) return;
      const s = o.service();
      if (!s) return sendJson(res, 503, MIDDLEWARE_MISSING);
      const report = s.health();
      sendJson(res, report.ok ? 200 : 503, report);
    },
    metrics: (req: http.IncomingMessage, res: http.ServerResponse) =>
      readOnly(req, res) &&
      gated(req, res, async (s) => {
        s.health(); // refreshes the gauges
        const text = await s.metrics();
        res.writeHead(200, { 'content-type': 'text/plain; version=0.0.4; charset=utf-8' });
        res.end(text);
      }),
    history: (req: http.IncomingMessage, res: http.ServerResponse) =>
      gated(req, res, async (s) => {
        if (!s.history)
          return sendJson(res, 503, { error: 'history needs storage: set INFLUX_URL' });
        req.url = req.url!.replace(/^\/api(?=\/)/, '');
        if (!(await s.history(req, res))) sendJson(res, 404, { error: 'not found' });
      }),
    async whoami(req: http.IncomingMessage, res: http.ServerResponse) {
      if (!o.auth.logins && o.auth.anonymous !== 'anywhere')
        return sendJson(res, 404, { error: 'no users file (ARMTWIN_USERS): no log-ins to tell' });
      const caller = o.auth.logins ? await o.authorize(req) : null;
      const a = whoamiAnswer(
        caller === null
          ? 'anonymous-demo'
          : caller.kind === 'user'
            ? { ok: true, principal: caller.principal }
            : { ok: false, lockedMs: caller.kind === 'refused' ? caller.lockedMs : 0 },
      );
      res.writeHead(a.status, a.headers).end(a.body);
    },
  };
}
