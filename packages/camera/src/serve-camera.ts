/**
 * A camera server on a port of its own (what `armtwin camera` runs): the HTTP(S) server, the
 * camera server's handlers on it, each camera announced on MQTT, and one `stop()` that removes
 * the announcements first (so no viewer comes back), then ends the viewers and ffmpeg.
 */
import http from 'node:http';
import https from 'node:https';
import type { AddressInfo } from 'node:net';
import {
  createCameraServer,
  type CameraServer,
  type CameraServerOptions,
} from './camera-server.ts';
import { startAnnouncer, type Announcer } from './announcer.ts';
import { OPEN_ACCESS } from './access.ts';

/** 127.0.0.0/8, ::1, localhost: the anonymous demo's only addresses. */
export const isLoopback = (host: string): boolean =>
  host === 'localhost' || host === '::1' || /^127\.\d+\.\d+\.\d+$/.test(host);

export interface ServeCameraOptions extends CameraServerOptions {
  /** Listen address. */
  host: string;
  /** Listen port (0 = any free one). */
  port: number;
  /** PEM certificate and key: HTTPS and WSS. */
  tls: { cert: string | Buffer; key: string | Buffer } | null;
  /** The base URL viewers reach this server at ('' = the listen address, http(s)://host:port). */
  publicUrl: string;
  /** The broker to announce on ('' = no announcements). */
  mqttUrl: string;
  /** Broker credentials ('' = anonymous). */
  username: string;
  password: string;
}

export const DEFAULT_SERVE_CAMERA_OPTIONS = {
  host: '127.0.0.1',
  port: 8090,
  tls: null,
  publicUrl: '',
  mqttUrl: '',
  username: '',
  password: '',
} satisfies Partial<ServeCameraOptions>;

export interface ServedCameras {
  /** The base URL announced. */
  url: string;
  port: number;
  server: CameraServer;
  announcers: Announcer[];
  /** Resolves once every announcement is acknowledged by the broker. */
  announced: Promise<void>;
  stop(): Promise<void>;
}

export async function serveCamera(
  options: Partial<ServeCameraOptions> & Pick<ServeCameraOptions, 'cameras'>,
): Promise<ServedCameras> {
  const o = { ...DEFAULT_SERVE_CAMERA_OPTIONS, ...options };
  const access = o.access ?? OPEN_ACCESS;
  if (!access.logins && !access.token && !isLoopback(o.host))
    throw new Error(
      `refusing to serve cameras to anyone on ${o.host}: beyond loopback the camera server needs a users file or a token`,
    );
  const cameras = createCameraServer(o);
  const handler = (req: http.IncomingMessage, res: http.ServerResponse) => {
    if (!cameras.handleRequest(req, res))
      res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
  };
  const httpServer = o.tls
    ? https.createServer({ cert: o.tls.cert, key: o.tls.key }, handler)
    : http.createServer(handler);
  httpServer.on('upgrade', (req, socket, head) => {
    if (!cameras.handleUpgrade(req, socket, head)) socket.destroy();
  });
  await new Promise<void>((resolve, reject) => {
    httpServer.once('error', reject);
    httpServer.listen(o.port, o.host, () => {
      httpServer.off('error', reject);
      resolve();
    });
  });
  const port = (httpServer.address() as AddressInfo).port;
  const host = o.host.includes(':') ? `[${o.host}]` : o.host === '0.0.0.0' ? '127.0.0.1' : o.host;
  const url = (o.publicUrl || `${o.tls ? 'https' : 'http'}://${host}:${port}`).replace(/\/+$/, '');
  cameras.start();
  const announcers = o.mqttUrl
    ? cameras.announcements(url).map((a) =>
        startAnnouncer({
          mqttUrl: o.mqttUrl,
          username: o.username,
          password: o.password,
          topic: a.topic,
          announcement: a.announcement,
          onFirst: o.onFirst,
          ...(o.log ? { log: o.log } : {}),
        }),
      )
    : [];
  let stopping: Promise<void> | null = null;
  return {
    url,
    port,
    server: cameras,
    announcers,
    announced: Promise.all(announcers.map((a) => a.announced)).then(() => {}),
    stop: () =>
      (stopping ??= (async () => {
        await Promise.all(announcers.map((a) => a.stop()));
        const closed = new Promise<void>((resolve) => httpServer.close(() => resolve()));
        await cameras.stop();
        httpServer.closeAllConnections();
        await closed;
      })()),
  };
}
