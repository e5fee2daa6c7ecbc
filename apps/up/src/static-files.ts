/**
 * Serves a built single-page app from a folder: files by path, `index.html` for any other GET
 * (client-side routes), a plain page saying what is missing when there is no build.
 */
import type http from 'node:http';
import path from 'node:path';
import { isFile, readPath, sendFile } from '@armtwin/http-api';

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.ico': 'image/x-icon',
  '.woff2': 'font/woff2',
  '.wasm': 'application/wasm',
  '.stl': 'model/stl',
  '.dae': 'model/vnd.collada+xml',
  '.urdf': 'application/xml',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.map': 'application/json',
  '.txt': 'text/plain; charset=utf-8',
};

export type Handler = (req: http.IncomingMessage, res: http.ServerResponse) => void;

/** `missing` is shown (as plain text) when `root` has no index.html. */
export function staticFiles(root: string, missing: string): Handler {
  const base = path.resolve(root);
  return (req, res) => {
    const pathname = readPath(req, res);
    if (pathname === null) return;
    let file = path.join(base, pathname);
    if (file !== base && !file.startsWith(base + path.sep)) {
      res.writeHead(403).end();
      return;
    }
    if (!isFile(file)) file = path.join(base, 'index.html');
    if (!isFile(file)) {
      res.writeHead(503, { 'content-type': 'text/plain; charset=utf-8' }).end(missing);
      return;
    }
    const type = TYPES[path.extname(file).toLowerCase()] ?? 'application/octet-stream';
    const cache = file.includes(`${path.sep}assets${path.sep}`)
      ? 'public, max-age=31536000, immutable'
      : 'no-cache';
    sendFile(req, res, file, type, cache);
  };
}
