/**
 * The history API over HTTP: `GET /history/{series,alarms,tracking,pose,audit,thermal-model}?…`
 * → JSON. The caller strips its own prefix (e.g. `/api`) and hands over everything else; the handler
 * answers false for paths outside `/history`. Dependencies are injected: the `HistoryReader`
 * (InfluxQL or Flux; a real one in integration tests), the clock.
 *
 *   200 JSON             the answer (see README.md)
 *   200 file             /history/export: the range as MCAP or CSV (an attachment)
 *   400 {error, parameter}  a bad parameter, named
 *   404 {error}          /history/<unknown>
 *   405                  not GET/HEAD
 *   502 {error}          InfluxDB failed or is unreachable
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import {
  EXPORT_FORMATS,
  exportRecording,
  loadRecordingRobot,
  storedProfile,
  type ExportFormat,
  type RecordingRobot,
} from '../export/index.ts';
import { auditCsv } from './audit-csv.ts';
import * as endpoints from './endpoints.ts';
import { DEFAULT_HISTORY_OPTIONS, type HistoryOptions } from './options.ts';
import { parseParams, type Endpoint, type HistoryParams } from './params.ts';
import type { HistoryReader } from './reader.ts';
import { thermalModel } from './thermal.ts';

export interface HistoryHandlerDeps {
  /** What runs the queries: `historyReader(source, language)` (./reader.ts). */
  reader: HistoryReader;
  /** Clock for `now` and relative times, epoch ms. Default `Date.now`. */
  now?: () => number;
  /** Limits; defaults in `DEFAULT_HISTORY_OPTIONS`. */
  options?: Partial<HistoryOptions>;
  /**
   * The robot of a profile name, for an MCAP export's joint states and transforms; throws when
   * there is none. Default: the profile folders of `public/models`.
   */
  robotFor?: (profile: string) => RecordingRobot;
  /** Told about each InfluxDB failure (the client still gets a 502). */
  onError?: (err: unknown, path: string) => void;
}

export type HistoryHandler = (req: IncomingMessage, res: ServerResponse) => Promise<boolean>;

const ROUTES: Record<
  Exclude<Endpoint, 'export'>,
  (ctx: endpoints.EndpointContext, p: HistoryParams) => Promise<unknown>
> = {
  series: endpoints.series,
  alarms: endpoints.alarms,
  tracking: endpoints.tracking,
  pose: endpoints.pose,
  audit: endpoints.audit,
  'thermal-model': thermalModel,
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
  const ctx: endpoints.EndpointContext = { reader: deps.reader, options };
  const robotFor = deps.robotFor ?? ((profile: string) => loadRecordingRobot(profile));

  /**
   * `/history/export?arm&start&stop&format=mcap|csv&profile=NAME`: the range as a download. An
   * MCAP without `profile` takes the one the arm announced, as stored with its history.
   */
  async function exportFile(
    res: ServerResponse,
    head: boolean,
    p: HistoryParams,
    query: URLSearchParams,
  ): Promise<void> {
    const format = (query.get('format') ?? 'mcap') as ExportFormat;
    if (!EXPORT_FORMATS.includes(format))
      return send(
        res,
        400,
        { error: `format must be ${EXPORT_FORMATS.join(' or ')}`, parameter: 'format' },
        head,
      );
    const profile = query.get('profile');
    let robot: RecordingRobot | null = null;
    if (profile !== null) {
      if (!PROFILE_NAME.test(profile))
        return send(
          res,
          400,
          { error: 'profile is not a profile name', parameter: 'profile' },
          head,
        );
      try {
        robot = { ...robotFor(profile), source: 'flag' };
      } catch (err) {
        return send(
          res,
          400,
          { error: (err as Error).message.split('\n')[0], parameter: 'profile' },
          head,
        );
      }
    } else if (format === 'mcap') {
      let announced: string | null;
      try {
        announced = await storedProfile(deps.reader, p.arm, p.stopMs);
      } catch (err) {
        deps.onError?.(err, '/history/export');
        const message = err instanceof Error ? err.message : String(err);
        return send(res, 502, { error: `InfluxDB query failed: ${message.slice(0, 300)}` }, head);
      }
      try {
        robot = announced ? { ...robotFor(announced), source: 'history' } : null;
      } catch {
        robot = null; // a profile this server has no folder for: positions and fields only
      }
    }
    const stamp = new Date(p.startMs).toISOString().replace(/[:.]/g, '-');
    res.writeHead(200, {
      'content-type': format === 'csv' ? 'text/csv; charset=utf-8' : 'application/octet-stream',
      'content-disposition': `attachment; filename="${p.arm}-${stamp}.${format}"`,
      'cache-control': 'no-store',
    });
    if (head) return void res.end();
    try {
      await exportRecording({
        reader: deps.reader,
        arm: p.arm,
        startMs: p.startMs,
        stopMs: p.stopMs,
        format,
        out: res,
        robot,
      });
      res.end();
    } catch (err) {
      deps.onError?.(err, '/history/export');
      res.destroy(err as Error); // the download fails visibly rather than ending short
    }
  }

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
    if (name !== 'export' && !Object.hasOwn(ROUTES, name)) {
      send(
        res,
        404,
        { error: `no such history endpoint; try ${[...Object.keys(ROUTES), 'export'].join(', ')}` },
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
    if (endpoint === 'export') {
      await exportFile(res, head, parsed.params, url.searchParams);
      return true;
    }
    const format = url.searchParams.get('format');
    if (endpoint === 'audit' && format !== null && format !== 'json' && format !== 'csv') {
      send(res, 400, { error: 'format must be json or csv', parameter: 'format' }, head);
      return true;
    }
    try {
      if (endpoint === 'audit' && format === 'csv') {
        const text = auditCsv((await endpoints.audit(ctx, parsed.params)).events);
        const stamp = new Date(parsed.params.startMs).toISOString().replace(/[:.]/g, '-');
        res.writeHead(200, {
          'content-type': 'text/csv; charset=utf-8',
          'content-disposition': `attachment; filename="${parsed.params.arm}-audit-${stamp}.csv"`,
          'cache-control': 'no-store',
        });
        res.end(head ? undefined : text);
        return true;
      }
      send(res, 200, await ROUTES[endpoint](ctx, parsed.params), head);
    } catch (err) {
      deps.onError?.(err, path);
      const message = err instanceof Error ? err.message : String(err);
      send(res, 502, { error: `InfluxDB query failed: ${message.slice(0, 300)}` }, head);
    }
    return true;
  };
}
