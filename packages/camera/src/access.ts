/**
 * Who may watch a camera. With neither a users file nor a token, anyone (the local demo). With
 * either, a request needs a log-in whose role may read the arm — viewer, operator and the middleware
 * (which records them) any arm, a device only its own — or the token, or the in-process
 * recorder's token (any arm).
 *
 * Credentials, first found wins:
 * - `Authorization: Basic <base64 name:password>` or `Authorization: Bearer <token>` (any client);
 * - the query parameters `auth=<base64 name:password>` (the same as Basic) or
 *   `access_token=<token>`, for browsers, whose `WebSocket` and `<img>` cannot send headers.
 *   A query string ends up in logs and histories that headers do not: the server never logs it,
 *   and a deployment with log-ins should use TLS (it needs it for WebCodecs anyway).
 * Log-ins go through the shared failed-log-in throttle (`LoginThrottle` of `@armtwin/auth`).
 */
import { createHash, timingSafeEqual } from 'node:crypto';
import { basicCredentials, type LoginThrottle, type Principal } from '@armtwin/auth';

export interface CameraAccess {
  /** The users file behind the log-in throttle; null = no log-ins. */
  logins: LoginThrottle | null;
  /** A bearer token that may watch every camera; '' = none. */
  token: string;
  /**
   * A bearer token of an in-process recorder: `armtwin up` mints one per run (never stored) for
   * its own middleware, which reaches the broker without a log-in and so has no password to
   * send. It may watch every camera, as the middleware role may.
   */
  recorderToken?: string;
}

export const OPEN_ACCESS: CameraAccess = { logins: null, token: '' };

export type Credentials =
  { type: 'basic'; name: string; password: string } | { type: 'bearer'; token: string };

export type AccessDecision =
  | { ok: true; who: string }
  | { ok: false; status: 401 | 403 | 429; message: string; retryAfterS?: number };

/** The credentials of a request: its Authorization header, else its query string. */
export function requestCredentials(
  authorization: string | undefined,
  url: string | undefined,
): Credentials | null {
  const bearer = /^Bearer +(\S+) *$/i.exec(authorization ?? '');
  if (bearer) return { type: 'bearer', token: bearer[1]! };
  const basic = basicCredentials(authorization);
  if (basic) return { type: 'basic', ...basic };
  const query = new URLSearchParams((url ?? '').split('?')[1] ?? '');
  const token = query.get('access_token');
  if (token) return { type: 'bearer', token };
  const auth = basicCredentials(`Basic ${query.get('auth') ?? ''}`);
  return auth ? { type: 'basic', ...auth } : null;
}

/** Whether this principal may watch the cameras of `armId` (null: every arm, as for metrics). */
export function mayWatch(p: Principal, armId: string | null): boolean {
  switch (p.role) {
    case 'viewer':
    case 'operator':
    case 'admin':
      return true;
    case 'middleware': // it records every camera (docs/cameras-recording.md)
      return true;
    case 'device':
      return armId !== null && p.arm === armId;
    default:
      return assertNever(p.role);
  }
}

const digest = (s: string) => createHash('sha256').update(s).digest();
const sameToken = (a: string, b: string) => timingSafeEqual(digest(a), digest(b));

/** Decides a request for the cameras of `armId` (null: the server's metrics). */
export async function authorize(
  access: CameraAccess,
  request: { authorization?: string; url?: string; address: string },
  armId: string | null,
): Promise<AccessDecision> {
  if (!access.logins && !access.token) return { ok: true, who: 'anonymous' };
  const creds = requestCredentials(request.authorization, request.url);
  if (!creds) return { ok: false, status: 401, message: 'log in to watch this camera' };
  if (creds.type === 'bearer') {
    if (access.recorderToken && sameToken(creds.token, access.recorderToken))
      return { ok: true, who: 'recorder' };
    return access.token && sameToken(creds.token, access.token)
      ? { ok: true, who: 'token' }
      : { ok: false, status: 401, message: 'wrong token' };
  }
  if (!access.logins)
    return { ok: false, status: 401, message: 'this server takes a token, not log-ins' };
  const r = await access.logins.login(request.address, creds.name, creds.password);
  if (!r.ok) {
    if (r.lockedMs > 0) {
      const retryAfterS = Math.ceil(r.lockedMs / 1000);
      return {
        ok: false,
        status: 429,
        message: `too many failed log-ins: try again in ${retryAfterS} s`,
        retryAfterS,
      };
    }
    return { ok: false, status: 401, message: 'wrong user name or password' };
  }
  if (!mayWatch(r.principal, armId))
    return {
      ok: false,
      status: 403,
      message: `${r.principal.role} ${r.principal.name} may not watch this camera`,
    };
  return { ok: true, who: r.principal.name };
}

function assertNever(x: never): never {
  throw new Error(`unhandled role ${String(x)}`);
}
