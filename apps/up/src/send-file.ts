/** Sending one file from disk, for the HUD's files and the robots' folders. */
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
