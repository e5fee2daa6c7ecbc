/**
 * `GET /models/<name>/…`: robot folders straight from disk, at request time, so a robot folder
 * added (imported, calibrated, its zones saved) while the server runs is served at once, without
 * rebuilding the HUD; by `armtwin up` and by the middleware (its MODELS_DIR). The folders are searched in order (an extra models folder
 * first, then the repository's `public/models`); the first that holds the file answers.
 * A missing file is a 404 (never the HUD's index.html), and nothing outside the folders is served.
 */
import type http from 'node:http';
import path from 'node:path';
import { isFile, readPath, sendFile } from './send-file.ts';

type Handler = (req: http.IncomingMessage, res: http.ServerResponse) => void;

/** The URL prefix robot folders are served under. */
export const MODELS_PREFIX = '/models/';

/** Content types of what a robot folder holds. */
export const MODEL_TYPES: Record<string, string> = {
  '.urdf': 'application/xml; charset=utf-8',
  '.xml': 'application/xml; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.stl': 'model/stl',
  '.dae': 'model/vnd.collada+xml',
  '.obj': 'model/obj',
  '.mtl': 'model/mtl',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
  '.tga': 'image/x-tga',
  '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/markdown; charset=utf-8',
};

/** The file a `/models/…` path names in `dir`, or null when it would leave `dir`. */
export function modelFilePath(dir: string, pathname: string): string | null {
  if (!pathname.startsWith(MODELS_PREFIX) || pathname.includes('\0')) return null;
  const base = path.resolve(dir);
  const file = path.resolve(base, '.' + path.posix.sep + pathname.slice(MODELS_PREFIX.length));
  return file.startsWith(base + path.sep) ? file : null;
}

/** A handler for `/models/…` reading from `dirs` (first match wins) on every request. */
export function modelFiles(dirs: readonly string[]): Handler {
  return (req, res) => {
    const pathname = readPath(req, res);
    if (pathname === null) return;
    const candidates = dirs.map((d) => modelFilePath(d, pathname));
    if (candidates.some((c) => c === null)) {
      res.writeHead(403, { 'content-type': 'text/plain; charset=utf-8' }).end('forbidden\n');
      return;
    }
    const file = candidates.find((c): c is string => c !== null && isFile(c));
    if (!file) {
      res
        .writeHead(404, {
          'content-type': 'text/plain; charset=utf-8',
          'cache-control': 'no-store',
        })
        .end(`no such model file: ${pathname}\n`);
      return;
    }
    const type = MODEL_TYPES[path.extname(file).toLowerCase()] ?? 'application/octet-stream';
    sendFile(req, res, file, type, 'no-cache');
  };
}
