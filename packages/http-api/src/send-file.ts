/** Reading a GET's path and sending one file from disk, for the HUD's files and the robots' folders. */
import fs from 'node:fs';
import type http from 'node:http';
import { byteRange, type ByteRange } from './byte-range.ts';

export function isFile(file: string): boolean {
  try {
    return fs.statSync(file).isFile();
  } catch {
    return false;
  }
}

/**
 * 200 with `type` and `cache` (the Cache-Control header); the body unless it is a HEAD. With
 * `ranges` (a file that never changes in place), a request's one byte range (./byte-range.ts) is
 * answered 206 with its Content-Range, one past the end 416, and `Accept-Ranges: bytes` says so.
 */
export function sendFile(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  file: string,
  type: string,
  cache: string,
  { ranges = false }: { ranges?: boolean } = {},
): void {
  const headers: http.OutgoingHttpHeaders = { 'content-type': type, 'cache-control': cache };
  let part: ByteRange | null = null;
  if (ranges) {
    let size: number;
    try {
      size = fs.statSync(file).size;
    } catch {
      res.writeHead(404).end();
      return;
    }
    const range = byteRange(req.headers.range, size);
    headers['accept-ranges'] = 'bytes';
    if (range === 'unsatisfiable') {
      res.writeHead(416, { ...headers, 'content-range': `bytes */${size}` }).end();
      return;
    }
    part = range;
    headers['content-length'] = range ? range.end - range.start + 1 : size;
    if (range) headers['content-range'] = `bytes ${range.start}-${range.end}/${size}`;
  }
  res.writeHead(part ? 206 : 200, headers);
  if (req.method === 'HEAD') {
    res.end();
    return;
  }
  fs.createReadStream(file, part ?? {})
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
