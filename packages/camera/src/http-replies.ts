/**
 * The camera server's fixed replies: the headers every camera response carries (open CORS, no
 * caching), a JSON refusal on a response, and a refusal written on a raw socket before a
 * WebSocket upgrade (where there is no response object yet).
 */
import type { ServerResponse } from 'node:http';
import type { Duplex } from 'node:stream';
import type { AccessDecision } from './access.ts';

/** Any origin may read a camera: no cookies are used, a log-in travels in each request. */
export const CORS = {
  'access-control-allow-origin': '*',
  'access-control-allow-headers': 'authorization',
  'access-control-expose-headers': 'x-timestamp, x-sequence',
};
export const NO_STORE = {
  'cache-control': 'no-store, no-cache, must-revalidate',
  pragma: 'no-cache',
};

const STATUS_TEXT: Record<number, string> = {
  401: 'Unauthorized',
  403: 'Forbidden',
  404: 'Not Found',
  429: 'Too Many Requests',
  500: 'Internal Server Error',
};

/** The extra headers of an access refusal: how to log in (401), when to try again (429). */
export function refusalHeaders(
  d: AccessDecision & { ok: false },
  logins: boolean,
): Record<string, string> {
  if (d.status === 401)
    return { 'www-authenticate': logins ? 'Basic realm="armtwin"' : 'Bearer realm="armtwin"' };
  return d.retryAfterS ? { 'retry-after': String(d.retryAfterS) } : {};
}

export function refuse(
  res: ServerResponse,
  status: number,
  message: string,
  extra: Record<string, string> = {},
): void {
  res.writeHead(status, { 'content-type': 'application/json', ...NO_STORE, ...CORS, ...extra });
  res.end(JSON.stringify({ error: message }));
}

/** Answers an upgrade request with a plain HTTP refusal and closes the socket. */
export function refuseUpgrade(
  socket: Duplex,
  status: number,
  text: string,
  extra: Record<string, string> = {},
): void {
  const headers = Object.entries({
    'content-type': 'text/plain',
    'content-length': String(Buffer.byteLength(text)),
    connection: 'close',
    ...extra,
  })
    .map(([k, v]) => `${k}: ${v}\r\n`)
    .join('');
  socket.end(`HTTP/1.1 ${status} ${STATUS_TEXT[status] ?? 'Error'}\r\n${headers}\r\n${text}`);
}
