/**
 * HTTP log-ins with the users file: the credentials of an `Authorization: Basic …` header, and
 * the answer to `GET …/whoami` (served by `armtwin up` and by the middleware when it has a
 * users file), which tells the HUD its role. Pure: the HTTP server writes what this returns.
 */
import type { WhoamiBody } from '@armtwin/api';
import type { LoginResult } from './throttle.ts';

/** `name:password` of an HTTP Basic header (UTF-8), or null when there is none or it is bad. */
export function basicCredentials(
  header: string | undefined,
): { name: string; password: string } | null {
  const m = /^Basic +([A-Za-z0-9+/=]+) *$/i.exec(header ?? '');
  if (!m) return null;
  const text = Buffer.from(m[1]!, 'base64').toString('utf8');
  const colon = text.indexOf(':');
  return colon < 0 ? null : { name: text.slice(0, colon), password: text.slice(colon + 1) };
}

export interface WhoamiAnswer {
  status: 200 | 401 | 429;
  headers: Record<string, string>;
  body: string;
}

/**
 * 200 `{name, role, arm?}` for a log-in (`{name: '', role: 'operator', anonymous: true}` in the
 * anonymous local demo), 401 without one, 429 with `Retry-After` while the address is locked
 * out. The broker enforces the role either way; this only lets the page say why a control is off.
 */
export function whoamiAnswer(result: LoginResult | 'anonymous-demo'): WhoamiAnswer {
  const headers = { 'content-type': 'application/json', 'cache-control': 'no-store' };
  if (result === 'anonymous-demo')
    return {
      status: 200,
      headers,
      body: JSON.stringify({ name: '', role: 'operator', anonymous: true } satisfies WhoamiBody),
    };
  if (result.ok)
    return { status: 200, headers, body: JSON.stringify(result.principal satisfies WhoamiBody) };
  if (result.lockedMs > 0) {
    const retry = Math.ceil(result.lockedMs / 1000);
    return {
      status: 429,
      headers: { ...headers, 'retry-after': String(retry) },
      body: JSON.stringify({
        error: `too many failed log-ins: try again in ${retry} s`,
      } satisfies WhoamiBody),
    };
  }
  return {
    status: 401,
    headers,
    body: JSON.stringify({ error: 'log in: HTTP Basic with a user' } satisfies WhoamiBody),
  };
}
