/**
 * The one HTTP(S) server of `armtwin up`: every answer carries the page's security headers; the
 * camera (if any) answers its own paths, /api and the robot folders (/models/…) are the API's,
 * everything else is the HUD's files; MQTT over WebSockets (and the camera's WebSockets) are
 * attached on the same port. `listenFront` resolves with the URL to open, or says which port is
 * taken.
 */
import http from 'node:http';
import https from 'node:https';
import type { Broker, BrokerTls } from '@armtwin/broker';
import type { createApi } from '@armtwin/http-api';
import type { CameraPart } from './camera-part.ts';
import { DEFAULT_HUD_HEADERS_OPTIONS, securityHeaders } from './security-headers.ts';
import type { Handler } from './static-files.ts';

export interface FrontOptions {
  broker: Broker;
  api: ReturnType<typeof createApi>;
  camera: CameraPart | null;
  /** The HUD's files (./static-files.ts). */
  files: Handler;
  tls: BrokerTls | null;
  /** Sources beyond this origin the page may use (./security-headers.ts). */
  cspSources: string[];
}

/** The server, its routes attached; not yet listening. */
export function createFront(o: FrontOptions): http.Server {
  const headers = Object.entries(
    securityHeaders({ ...DEFAULT_HUD_HEADERS_OPTIONS, extraSources: o.cspSources }),
  );
  const onRequest = (req: http.IncomingMessage, res: http.ServerResponse) => {
    for (const [name, value] of headers) res.setHeader(name, value);
    if (o.camera?.handleRequest(req, res)) return;
    if (req.url === '/api' || req.url?.startsWith('/api/')) {
      if (!o.api.handle(req, res))
        res
          .writeHead(404, { 'content-type': 'application/json', 'cache-control': 'no-store' })
          .end(JSON.stringify({ error: 'not found' }));
      return;
    }
    // The robot folders (`/models/…`) are the API's too; everything else is the HUD's.
    if (req.url?.startsWith('/models/') && o.api.handle(req, res)) return;
    o.files(req, res);
  };
  const server = o.tls
    ? https.createServer({ ...o.tls, minVersion: 'TLSv1.2' }, onRequest)
    : http.createServer(onRequest);
  o.broker.attach(server, o.camera ? [o.camera.handleUpgrade] : []);
  return server;
}

/** Listens on `port` of `host`; the URL to open (a taken port: an error that says what to set). */
export async function listenFront(
  server: http.Server,
  port: number,
  host: string,
  tls: boolean,
): Promise<string> {
  try {
    await new Promise<void>((resolve, reject) => {
      server.once('error', reject);
      server.listen(port, host, () => resolve());
    });
  } catch (err) {
    throw (err as NodeJS.ErrnoException).code === 'EADDRINUSE'
      ? new Error(`HTTP port ${port} is taken: set ARMTWIN_PORT to another port`)
      : err;
  }
  const address = server.address();
  const httpPort = typeof address === 'object' && address ? address.port : port;
  const shownHost = host === '0.0.0.0' || host === '::' ? 'localhost' : host;
  return `${tls ? 'https' : 'http'}://${shownHost}:${httpPort}/`;
}
