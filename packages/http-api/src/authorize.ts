/**
 * The API's one log-in step (SECURITY.md): `authorize(request) → caller`, from the request's
 * `Authorization` header, checked against the users file through the failed-log-in throttle
 * (the same one the embedded broker uses under `armtwin up`) or the API token; then
 * `refusal(caller, right)` says whether that caller may do what a route needs:
 *
 * - `data` (`/metrics`, `/history`): open when there is neither an API token nor a users file;
 *   else the token or any user's log-in.
 * - `view` (whether a model copy runs): any user or the token; anonymous where anonymous may.
 * - `change` (robot imports, calibration, keep-out zones, model copies): an operator's or an
 *   admin's log-in; anonymous callers only without a users file, and then only from where
 *   `anonymous` allows (`anywhere`: `armtwin up`'s local demo, whose server refuses any
 *   non-loopback host without users; `loopback`: the middleware, which may listen wider).
 *
 * A locked-out address is told so (429) whatever the route.
 */
import { createHash, timingSafeEqual } from 'node:crypto';
import type http from 'node:http';
import { basicCredentials, type LoginThrottle, type Principal } from '@armtwin/auth';

export interface AuthOptions {
  /** The users file behind the failed-log-in throttle; null = no log-ins. */
  logins: LoginThrottle | null;
  /** API_TOKEN: a bearer token that opens `data` and `view` ('' = none). */
  apiToken: string;
  /** Without a users file, where an anonymous caller may change robots and model copies. */
  anonymous: 'anywhere' | 'loopback';
}

export type Caller =
  | { kind: 'user'; principal: Principal }
  | { kind: 'token' }
  | { kind: 'anonymous' }
  /** Credentials that did not check out; `lockedMs` > 0 while the address is locked out. */
  | { kind: 'refused'; lockedMs: number };

export type Right = 'data' | 'view' | 'change';

export interface Refusal {
  status: 401 | 403 | 429;
  error: string;
  /** Seconds, with a 429. */
  retryAfterS?: number;
}

export type Authorize = (req: http.IncomingMessage) => Promise<Caller>;

const digest = (s: string) => createHash('sha256').update(s).digest();

/** Whether the request carries `Authorization: Bearer <token>` (compared in constant time). */
export function hasBearer(req: http.IncomingMessage, token: string): boolean {
  const m = /^Bearer +(\S+) *$/i.exec(req.headers.authorization ?? '');
  return m !== null && timingSafeEqual(digest(m[1]!), digest(token));
}

/** The one log-in step: who the request's `Authorization` header says the caller is. */
export function createAuthorize(o: AuthOptions): Authorize {
  return async (req) => {
    const header = req.headers.authorization ?? '';
    if (o.apiToken && /^Bearer /i.test(header))
      return hasBearer(req, o.apiToken) ? { kind: 'token' } : { kind: 'refused', lockedMs: 0 };
    if (!o.logins || !/^Basic /i.test(header)) return { kind: 'anonymous' };
    const creds = basicCredentials(header);
    if (!creds) return { kind: 'refused', lockedMs: 0 };
    const r = await o.logins.login(addressOf(req), creds.name, creds.password);
    return r.ok
      ? { kind: 'user', principal: r.principal }
      : { kind: 'refused', lockedMs: r.lockedMs };
  };
}

/** Why `caller` may not do what needs `right` (null: it may). */
export function refusal(
  o: AuthOptions,
  req: http.IncomingMessage,
  caller: Caller,
  right: Right,
): Refusal | null {
  if (caller.kind === 'refused' && caller.lockedMs > 0) {
    const retryAfterS = Math.ceil(caller.lockedMs / 1000);
    return {
      status: 429,
      error: `too many failed log-ins: try again in ${retryAfterS} s`,
      retryAfterS,
    };
  }
  if (right === 'data') {
    if (!o.apiToken && !o.logins) return null;
    if (caller.kind === 'token' || caller.kind === 'user') return null;
    const how = o.logins
      ? 'log-in required: a log-in (HTTP Basic) or Authorization: Bearer <API_TOKEN>'
      : 'API token required: Authorization: Bearer <API_TOKEN>';
    return { status: 401, error: how };
  }
  const anonymousMay =
    !o.logins && (o.anonymous === 'anywhere' || isLoopback(req.socket?.remoteAddress));
  if (caller.kind === 'anonymous' && anonymousMay) return null;
  if (right === 'view') {
    if (caller.kind === 'token' || caller.kind === 'user') return null;
    return { status: 401, error: 'log in' };
  }
  if (caller.kind === 'user') {
    const { role } = caller.principal;
    return role === 'operator' || role === 'admin'
      ? null
      : { status: 403, error: `${role}s may not change a robot` };
  }
  if (caller.kind === 'token')
    return { status: 403, error: 'the API token may only read: log in as an operator' };
  if (caller.kind === 'anonymous' && !o.logins)
    return {
      status: 403,
      error: 'without a users file (ARMTWIN_USERS) robots are changed from this machine only',
    };
  return { status: 401, error: 'log in as an operator' };
}

const addressOf = (req: http.IncomingMessage) => req.socket?.remoteAddress ?? 'unknown';

/** 127.0.0.0/8, ::1 and their IPv4-mapped forms. */
export function isLoopback(address: string | undefined): boolean {
  if (!address) return false;
  const v4 = address.startsWith('::ffff:') ? address.slice(7) : address;
  return v4 === '::1' || /^127\.\d+\.\d+\.\d+$/.test(v4);
}

/** The name a caller acts under: a user's, `token` or `anonymous` (refused callers: ''). */
export function nameOf(caller: Caller): string {
  if (caller.kind === 'user') return caller.principal.name;
  return caller.kind === 'refused' ? '' : caller.kind;
}
