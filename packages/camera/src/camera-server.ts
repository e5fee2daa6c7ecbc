/**
 * The camera server: its cameras' ffmpegs and viewers behind an HTTP request handler and a
 * WebSocket upgrade handler, which `serveCamera` puts on a port of their own and `armtwin up`
 * can mount on its one HTTP port. Routes (`{camId}` = `[a-z0-9-]{1,32}`):
 *
 * - `GET /camera/{camId}.mjpeg`: `multipart/x-mixed-replace`, one JPEG per part with its
 *   `Content-Length`, `X-Timestamp` (the frame's capture time, epoch ms) and `X-Sequence`;
 * - `GET /camera/{camId}.jpg`: the latest JPEG alone;
 * - WebSocket `/camera/{camId}.h264`: `h264-ws` (./wire.ts);
 * - `GET /camera/metrics`: the counters, JSON (`CameraServerStats`).
 *
 * With a users file or a token every route needs a log-in (./access.ts); CORS is open (`*`, no
 * cookies are used) so a HUD on another port can read the pixels.
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { Duplex } from 'node:stream';
import type { Logger } from 'pino';
import { WebSocket, WebSocketServer } from 'ws';
import type { CameraAnnouncement, CameraKind } from './announcement.ts';
import { authorize, OPEN_ACCESS, type AccessDecision, type CameraAccess } from './access.ts';
import {
  DEFAULT_CAMERA_FEED_OPTIONS,
  MJPEG_CONTENT_TYPE,
  type CameraFeedOptions,
} from './camera-feed.ts';
import { CameraUnit, type CameraSpec, type CameraStats } from './camera-unit.ts';
import { CORS, NO_STORE, refusalHeaders, refuse as reply, refuseUpgrade } from './http-replies.ts';
import { DEFAULT_ENCODER_OPTIONS, type EncoderOptions } from './ffmpeg-args.ts';
import { DEFAULT_BACKOFF, type BackoffOptions } from './ffmpeg-runner.ts';

export interface CameraServerOptions {
  cameras: CameraSpec[];
  /** The ffmpeg program. */
  ffmpeg: string;
  encoder: Partial<EncoderOptions>;
  feed: Partial<CameraFeedOptions>;
  /** Restart back-off of a failing ffmpeg. */
  backoff: BackoffOptions;
  /** A source with no frame for this long has its ffmpeg restarted, ms. */
  stallMs: number;
  access: CameraAccess;
  /** WebSocket ping period; a viewer that misses a pong is dropped, ms. */
  pingMs: number;
  now: () => number;
  /** Told the first time each kind of problem happens (later ones are only counted). */
  onFirst: (kind: string, message: string) => void;
  log?: Logger;
}

export const DEFAULT_CAMERA_SERVER_OPTIONS = {
  ffmpeg: 'ffmpeg',
  encoder: DEFAULT_ENCODER_OPTIONS,
  feed: DEFAULT_CAMERA_FEED_OPTIONS,
  backoff: DEFAULT_BACKOFF,
  stallMs: 10_000,
  access: OPEN_ACCESS,
  pingMs: 20_000,
  now: Date.now,
  onFirst: () => {},
} satisfies Partial<CameraServerOptions>;

export interface CameraServerStats {
  cameras: CameraStats[];
  /** Requests refused, by HTTP status (401, 403, 404, 429, 503 too many viewers). */
  refused: Record<string, number>;
}

export interface CameraServer {
  /** Serves the request if it is under `/camera/` (returns true), else leaves it. */
  handleRequest(req: IncomingMessage, res: ServerResponse): boolean;
  /** Takes the upgrade if it is a camera's WebSocket (returns true), else leaves it. */
  handleUpgrade(req: IncomingMessage, socket: Duplex, head: Buffer): boolean;
  /** Each camera's topic and announcement, its URLs under `baseUrl` (`http(s)://host:port`). */
  announcements(
    baseUrl: string,
  ): { armId: string; camId: string; topic: string; announcement: CameraAnnouncement }[];
  stats(): CameraServerStats;
  /** The pid of a camera's ffmpeg now, or null. */
  ffmpegPid(camId: string): number | null;
  start(): void;
  /** Ends every viewer and stops every ffmpeg. */
  stop(): Promise<void>;
}

const ROUTE = /^\/camera\/([a-z0-9-]{1,32})\.(mjpeg|jpg|h264)$/;
export function createCameraServer(
  options: Partial<CameraServerOptions> & Pick<CameraServerOptions, 'cameras'>,
): CameraServer {
  const o: CameraServerOptions = { ...DEFAULT_CAMERA_SERVER_OPTIONS, ...options };
  const units = new Map<string, CameraUnit>();
  for (const spec of o.cameras) {
    if (units.has(spec.camId)) throw new RangeError(`two cameras named ${spec.camId}`);
    units.set(spec.camId, new CameraUnit(spec, o));
  }
  const refused: Record<string, number> = {};
  const streaming = new Set<ServerResponse>(); // open MJPEG responses, ended by stop()
  const wss = new WebSocketServer({ noServer: true, perMessageDeflate: false, maxPayload: 1024 });
  const alive = new WeakMap<WebSocket, boolean>();
  let pinger: ReturnType<typeof setInterval> | null = null;
  const address = (req: IncomingMessage) => req.socket.remoteAddress ?? 'unknown';
  const check = (req: IncomingMessage, armId: string | null) =>
    authorize(
      o.access,
      { authorization: req.headers.authorization, url: req.url, address: address(req) },
      armId,
    );

  const refuse = (
    res: ServerResponse,
    status: number,
    message: string,
    extra: Record<string, string> = {},
  ) => {
    refused[status] = (refused[status] ?? 0) + 1;
    reply(res, status, message, extra);
  };
  const rejectUpgrade = (
    socket: Duplex,
    status: number,
    text: string,
    extra: Record<string, string> = {},
  ) => {
    refused[status] = (refused[status] ?? 0) + 1;
    refuseUpgrade(socket, status, text, extra);
  };
  const howToLogIn = (d: AccessDecision & { ok: false }) => refusalHeaders(d, !!o.access.logins);

  function serveMjpeg(req: IncomingMessage, res: ServerResponse, unit: CameraUnit): void {
    if (unit.feed.full('mjpeg')) {
      unit.count('viewer-refused', 'too many viewers');
      return refuse(res, 503, 'too many viewers of this camera');
    }
    res.writeHead(200, {
      'content-type': MJPEG_CONTENT_TYPE,
      ...NO_STORE,
      ...CORS,
      'x-content-type-options': 'nosniff',
    });
    res.socket?.setNoDelay(true);
    const viewer = unit.feed.watchMjpeg(
      { write: (data, done) => void res.write(data, (err) => done(err)) },
      address(req),
      o.now(),
    );
    streaming.add(res);
    res.on('close', () => {
      streaming.delete(res);
      if (viewer) unit.feed.unwatch('mjpeg', viewer);
    });
  }

  function serveSnapshot(res: ServerResponse, unit: CameraUnit): void {
    const snap = unit.feed.snapshot;
    if (!snap) return refuse(res, 503, 'no picture yet');
    res.writeHead(200, {
      'content-type': 'image/jpeg',
      'x-timestamp': String(snap.at),
      ...NO_STORE,
      ...CORS,
    });
    res.end(snap.jpeg);
  }

  function attachH264(ws: WebSocket, req: IncomingMessage, unit: CameraUnit): void {
    alive.set(ws, true);
    ws.on('pong', () => alive.set(ws, true));
    ws.on('error', (err) => unit.count('ws-error', err.message));
    const viewer = unit.feed.watchH264(
      {
        write: (data, done) =>
          ws.readyState === WebSocket.OPEN
            ? ws.send(data, { binary: true }, done)
            : done(new Error('closed')),
      },
      address(req),
      o.now(),
    );
    if (!viewer) {
      unit.count('viewer-refused', 'too many viewers');
      ws.close(1013, 'too many viewers');
      return;
    }
    ws.on('close', () => unit.feed.unwatch('h264-ws', viewer));
  }

  const server: CameraServer = {
    handleRequest(req, res) {
      const path = (req.url ?? '/').split('?')[0]!;
      if (path !== '/camera' && !path.startsWith('/camera/')) return false;
      if (req.method === 'OPTIONS') {
        res
          .writeHead(204, {
            ...CORS,
            'access-control-allow-methods': 'GET',
            'access-control-max-age': '600',
          })
          .end();
        return true;
      }
      if (req.method !== 'GET') {
        res.writeHead(405, { allow: 'GET, OPTIONS', ...CORS }).end();
        return true;
      }
      const m = ROUTE.exec(path);
      const unit = m ? units.get(m[1]!) : undefined;
      const kind: CameraKind | 'metrics' | null =
        path === '/camera/metrics' ? 'metrics' : m?.[2] === 'h264' ? 'h264-ws' : m ? 'mjpeg' : null;
      if (kind === null || (kind !== 'metrics' && !unit?.serves(kind))) {
        refuse(res, 404, 'no such camera stream');
        return true;
      }
      if (kind === 'h264-ws') {
        refuse(res, 426, 'this is a WebSocket', { upgrade: 'websocket' });
        return true;
      }
      check(req, unit?.spec.armId ?? null).then(
        (d) => {
          if (!d.ok) return refuse(res, d.status, d.message, howToLogIn(d));
          if (kind === 'metrics') {
            res.writeHead(200, { 'content-type': 'application/json', ...NO_STORE, ...CORS });
            return void res.end(JSON.stringify(server.stats()));
          }
          if (m![2] === 'jpg') return serveSnapshot(res, unit!);
          serveMjpeg(req, res, unit!);
        },
        (err: Error) => {
          unit?.count('access-check', err.message);
          if (!res.headersSent) refuse(res, 500, 'log-in check failed');
        },
      );
      return true;
    },

    handleUpgrade(req, socket, head) {
      const path = (req.url ?? '/').split('?')[0]!;
      if (!path.startsWith('/camera/')) return false;
      const m = ROUTE.exec(path);
      const unit = m?.[2] === 'h264' ? units.get(m[1]!) : undefined;
      if (!unit?.serves('h264-ws')) {
        rejectUpgrade(socket, 404, 'no such camera stream');
        return true;
      }
      socket.on('error', (err) => unit.count('ws-error', err.message));
      check(req, unit.spec.armId).then(
        (d) => {
          if (!d.ok) return rejectUpgrade(socket, d.status, d.message, howToLogIn(d));
          wss.handleUpgrade(req, socket, head, (ws) => attachH264(ws, req, unit));
        },
        (err: Error) => {
          unit.count('access-check', err.message);
          rejectUpgrade(socket, 500, 'log-in check failed');
        },
      );
      return true;
    },

    announcements(baseUrl) {
      return [...units.values()].map((u) => ({
        armId: u.spec.armId,
        camId: u.spec.camId,
        topic: u.topic,
        announcement: u.announcement(baseUrl),
      }));
    },

    stats: () => ({ cameras: [...units.values()].map((u) => u.stats()), refused: { ...refused } }),

    ffmpegPid: (camId) => units.get(camId)?.runner?.pid ?? null,

    start() {
      for (const u of units.values()) u.runner?.start();
      pinger ??= setInterval(() => {
        for (const ws of wss.clients) {
          if (alive.get(ws) === false) ws.terminate();
          else {
            alive.set(ws, false);
            ws.ping();
          }
        }
      }, o.pingMs);
    },

    async stop() {
      if (pinger) clearInterval(pinger);
      pinger = null;
      for (const ws of wss.clients) ws.terminate();
      for (const res of streaming) res.destroy();
      await Promise.all([...units.values()].map((u) => u.runner?.stop()));
      await new Promise<void>((resolve) => wss.close(() => resolve()));
    },
  };
  return server;
}
