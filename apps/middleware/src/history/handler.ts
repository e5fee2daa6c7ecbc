/**
 * The history API over HTTP: `GET /history/{series,alarms,tracking,pose}?…` → JSON. The
 * caller strips its own prefix (e.g. `/api`) and hands over everything else; the handler
 * answers false for paths outside `/history`. Dependencies are injected: the QueryApi of
 * @influxdata/influxdb-client (a real one in integration tests), the bucket, the clock.
 *
 *   200 JSON             the answer (see README.md)
 *   400 {error, parameter}  a bad parameter, named
 *   404 {error}          /history/<unknown>
 *   405                  not GET/HEAD
 *   502 {error}          InfluxDB failed or is unreachable
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { QueryApi } from '@influxdata/influxdb-client';
import * as endpoints from './endpoints.ts';
import { DEFAULT_HISTORY_OPTIONS, type HistoryOptions } from './options.ts';
import { parseParams, type Endpoint, type HistoryParams } from './params.ts';

export interface HistoryHandlerDeps {
  /** `new InfluxDB({url, token}).getQueryApi(org)`. */
  queryApi: QueryApi;
  /** 2.x bucket, or `db/rp` on 1.8 (`armtwin/autogen`). */
  bucket: string;
  /** Clock for `now` and relative times, epoch ms. Default `Date.now`. */
  now?: () => number;
  /** Limits; defaults in `DEFAULT_HISTORY_OPTIONS`. */
  options?: Partial<HistoryOptions>;
  /** Told about each InfluxDB failure (the client still gets a 502). */
  onError?: (err: unknown, path: string) => void;
}

export type HistoryHandler = (req: IncomingMessage, res: ServerResponse) => Promise<boolean>;

const ROUTES: Record<
  Endpoint,
  (ctx: endpoints.EndpointContext, p: HistoryParams) => Promise<unknown>
> = {
  series: endpoints.series,
  alarms: endpoints.alarms,
  tracking: endpoints.tracking,
  pose: endpoints.pose,
};

function send(res: ServerResponse, status: number, body: unknown, head = false): void {
  const text = JSON.stringify(body);
  res.writeHead(status, {
    'content-type': 'application/json; charset=utf-8',
    'cache-control': 'no-store',
    'content-length': Buffer.byteLength(text),
  });
  res.end(head ? undefined : text);
}

export function createHistoryHandler(deps: HistoryHandlerDeps): HistoryHandler {
  const options: HistoryOptions = { ...DEFAULT_HISTORY_OPTIONS, ...deps.options };
  const now = deps.now ?? Date.now;
  const ctx: endpoints.EndpointContext = { queryApi: deps.queryApi, bucket: deps.bucket, options };
  return async (req, res) => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    const path = url.pathname;
    if (path !== '/history' && !path.startsWith('/history/')) return false;
    if (req.method !== 'GET' && req.method !== 'HEAD') {
      res.writeHead(405, { allow: 'GET, HEAD' }).end();
      return true;
    }
    const head = req.method === 'HEAD';
    const name = path.slice('/history/'.length);
    if (!Object.hasOwn(ROUTES, name)) {
      send(
        res,
        404,
        { error: `no such history endpoint; try ${Object.keys(ROUTES).join(', ')}` },
        head,
      );
      return true;
    }
    const endpoint = name as Endpoint;
    const parsed = parseParams(endpoint, url.searchParams, now(), options.maxSpanMs);
    if (!parsed.ok) {
      send(res, 400, { error: parsed.error, parameter: parsed.parameter }, head);
      return true;
    }
    try {
      send(res, 200, await ROUTES[endpoint](ctx, parsed.params), head);
    } catch (err) {
      deps.onError?.(err, path);
      const message = err instanceof Error ? err.message : String(err);
      send(res, 502, { error: `InfluxDB query failed: ${message.slice(0, 300)}` }, head);
    }
    return true;
  };
}
