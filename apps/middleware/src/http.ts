/**
 * `/healthz` (JSON, 200 or 503) and `/metrics` (Prometheus text). Works at the root of its
 * own port and mounted under `/api` on another server (the `npm start` orchestrator).
 * `/history/…` is the history API (./history), present when storage is configured.
 * With an API token, everything but `/healthz` needs `Authorization: Bearer <token>` (401).
 * With a users file (`logins`), `/whoami` answers the HUD's log-in, and a user's HTTP Basic
 * log-in opens `/metrics` and `/history` too (which then always need one or the other).
 */
import { createHash, timingSafeEqual } from 'node:crypto';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { basicCredentials, whoamiAnswer, type LoginThrottle } from '@armtwin/auth';
import type { HistoryHandler } from './history/index.ts';
import { renderMetrics, type Metrics } from './metrics.ts';

export interface HealthReport {
  ok: boolean;
  /** `broker`: "Broker 2 of 2: mqtt://…" (docs/protocol.md § Several brokers). */
  mqtt: { connected: boolean; url: string; broker?: string };
  influx: { reachable: boolean; url: string };
  storage: boolean;
  writeMode: 'batch' | 'sync';
  spool: { files: number; points: number; bytes: number; full: boolean; openPoints: number };
  pointsWritten: number;
  pointsDropped: number;
}

/** What the handler needs from a running middleware. */
export interface HttpSource {
  metrics: Metrics;
  health(): HealthReport;
  /** The history API, or null when there is no storage to read from. */
  history?: HistoryHandler | null;
  /** '' = open; else the bearer token /metrics and /history require. */
  apiToken?: string;
  /** The users file behind the failed-log-in throttle, or null. */
  logins?: LoginThrottle | null;
}

const digest = (s: string) => createHash('sha256').update(s).digest();

/** Whether the request carries `Authorization: Bearer <token>` (compared in constant time). */
export function hasBearer(req: IncomingMessage, token: string): boolean {
  const m = /^Bearer +(\S+) *$/i.exec(req.headers.authorization ?? '');
  return m !== null && timingSafeEqual(digest(m[1]!), digest(token));
}

function unauthorised(res: ServerResponse, users: boolean): true {
  res.writeHead(401, {
    'content-type': 'application/json',
    'www-authenticate': users ? 'Basic realm="armtwin"' : 'Bearer realm="armtwin"',
    'cache-control': 'no-store',
  });
  const how = users
    ? 'a log-in (HTTP Basic) or Authorization: Bearer <API_TOKEN>'
    : 'Authorization: Bearer <API_TOKEN>';
  res.end(JSON.stringify({ error: `${users ? 'log-in' : 'API token'} required: ${how}` }));
  return true;
}

const address = (req: IncomingMessage) => req.socket.remoteAddress ?? 'unknown';

export type HttpHandler = (req: IncomingMessage, res: ServerResponse) => boolean;

/** Serves the request if it is one of ours (returns true), else leaves it (returns false). */
export function createHttpHandler(mw: HttpSource): HttpHandler {
  const logins = mw.logins ?? null;
  const serve = (req: IncomingMessage, res: ServerResponse, path: string): boolean => {
    const isHistory = path === '/history' || path.startsWith('/history/');
    if (isHistory) {
      if (!mw.history) {
        res.writeHead(503, { 'content-type': 'application/json' });
        res.end(JSON.stringify({ error: 'history needs storage: set INFLUX_URL' }));
        return true;
      }
      req.url = req.url!.replace(/^\/api(?=\/)/, '');
      mw.history(req, res).then(
        (mine) =>
          mine ||
          res.writeHead(404, { 'content-type': 'application/json' }).end('{"error":"not found"}'),
        () => res.headersSent || res.writeHead(500).end(),
      );
      return true;
    }
    if (req.method !== 'GET' && req.method !== 'HEAD') {
      if (path !== '/healthz' && path !== '/metrics') return false;
      res.writeHead(405, { allow: 'GET, HEAD' }).end();
      return true;
    }
    if (path === '/healthz') {
      const report = mw.health();
      res.writeHead(report.ok ? 200 : 503, {
        'content-type': 'application/json',
        'cache-control': 'no-store',
      });
      res.end(JSON.stringify(report));
      return true;
    }
    if (path === '/metrics') {
      mw.health(); // refreshes the gauges
      res.writeHead(200, { 'content-type': 'text/plain; version=0.0.4; charset=utf-8' });
      res.end(renderMetrics(mw.metrics));
      return true;
    }
    return false;
  };
  /** Checks an HTTP Basic log-in, then serves or refuses (401, or 429 while locked out). */
  const afterLogIn = (req: IncomingMessage, res: ServerResponse, path: string, who: boolean) => {
    const creds = basicCredentials(req.headers.authorization);
    const check = creds
      ? logins!.login(address(req), creds.name, creds.password)
      : Promise.resolve({ ok: false as const, lockedMs: 0 });
    check.then(
      (r) => {
        if (who) {
          const a = whoamiAnswer(r);
          res.writeHead(a.status, a.headers).end(a.body);
        } else if (r.ok) serve(req, res, path);
        else if (r.lockedMs > 0) {
          const a = whoamiAnswer(r);
          res.writeHead(a.status, a.headers).end(a.body);
        } else unauthorised(res, true);
      },
      () => res.headersSent || res.writeHead(500).end(),
    );
    return true;
  };
  return (req, res) => {
    const path = (req.url ?? '/').split('?')[0]!.replace(/^\/api(?=\/)/, '');
    if (path === '/whoami' && logins) return afterLogIn(req, res, path, true);
    const guarded =
      (mw.apiToken || logins) &&
      (path === '/metrics' || path === '/history' || path.startsWith('/history/'));
    if (!guarded || (mw.apiToken && hasBearer(req, mw.apiToken))) return serve(req, res, path);
    if (!logins) return unauthorised(res, false);
    return afterLogIn(req, res, path, false);
  };
}
