/** Reading a GET's path and sending one file from disk, for the HUD's files and the robots' folders. */
import fs from 'node:fs';
import type http from 'node:http';

export function isFile(file: string): boolean {
  try {
    return fs.statSync(file).isFile();
  } catch {
    return false;
  }
}

/** 200 with `type` and `cache` (the Cache-Control header); the body unless it is a HEAD. */
export function sendFile(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  file: string,
  type: string,
  cache: string,
): void {
  res.writeHead(200, { 'content-type': type, 'cache-control': cache });
  if (req.method === 'HEAD') {
    res.end();
    return;
  }
  fs.createReadStream(file)
    .on('error', () => res.destroy())
    .pipe(res);
}

/**
 * The decoded path of a GET or HEAD request, or null after answering 405 (another method) or
 * 400 (a path that does not decode).
 */
export function readPath(req: http.IncomingMessage, res: http.ServerResponse): string | null {
  if (req.method !== 'GET' && req.method !== 'HEAD') {
    res.writeHead(405, { allow: 'GET, HEAD' }).end();
    return null;
  }
  try {
    return decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
  } catch {
    res.writeHead(400).end();
    return null;
  }
}
