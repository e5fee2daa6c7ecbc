/**
 * A tiny static file server for the built HUD (apps/web/dist) on a free port of 127.0.0.1:
 * what `npm start` serves, without the broker or the API (so /api/healthz is a 404 and the
 * HUD must say "history storage off"). Every answer carries the security headers `armtwin up`
 * sends (apps/up/src/security-headers.ts), with the loopback brokers and camera servers the
 * tests start as extra sources, so a page that needs something the policy blocks fails here too.
 */
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import type { AddressInfo } from 'node:net';
import { proxyRequest } from './api-proxy.ts';
import { securityHeaders } from '../../../apps/up/src/security-headers.ts';

/** The tests' brokers and camera servers: any port of the loopback address. */
export const TEST_CSP_SOURCES = ['http://127.0.0.1:*', 'ws://127.0.0.1:*'];

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.urdf': 'application/xml',
  '.stl': 'model/stl',
  '.svg': 'image/svg+xml',
  '.json': 'application/json',
};

export interface StaticServer {
  url: string;
  close(): Promise<void>;
}

/** `proxy`: requests under `prefix` (e.g. `/api/`) go to `target` (the middleware), as `npm start` does. */
export async function serveStatic(
  root: string,
  opts: { proxy?: { prefix: string; target: string } } = {},
): Promise<StaticServer> {
  const base = path.resolve(root);
  const headers = Object.entries(securityHeaders({ extraSources: TEST_CSP_SOURCES }));
  const server = http.createServer((req, res) => {
    for (const [name, value] of headers) res.setHeader(name, value);
    if (opts.proxy && (req.url ?? '').startsWith(opts.proxy.prefix)) {
      proxyRequest(req, res, opts.proxy.target);
      return;
    }
    const pathname = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
    const file = path.resolve(
      base,
      `.${pathname.endsWith('/') ? `${pathname}index.html` : pathname}`,
    );
    if (!file.startsWith(base + path.sep)) {
      res.writeHead(403).end();
      return;
    }
    fs.readFile(file, (err, body) => {
      if (err) {
        res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
        return;
      }
      res
        .writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' })
        .end(body);
    });
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}/`,
    close: () =>
      new Promise<void>((resolve) => {
        server.closeAllConnections();
        server.close(() => resolve());
      }),
  };
}
