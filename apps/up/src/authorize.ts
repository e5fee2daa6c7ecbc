/**
 * Who may use `armtwin up`'s own routes, checked against the same log-ins as the broker (HTTP
 * Basic through its failed-log-in throttle, SECURITY.md); in the anonymous local demo
 * (`logins` null) anyone is an operator. Also `/api/whoami` for the HUD, and the hand-over of a
 * Basic log-in to the middleware as its bearer token.
 */
import type http from 'node:http';
import {
  basicCredentials,
  whoamiAnswer,
  type LoginResult,
  type LoginThrottle,
} from '@armtwin/auth';
import type { Authorize } from './calibration-route.ts';

/** The log-in named by an HTTP Basic header, through the throttle the broker uses. */
export async function basicUser(
  req: http.IncomingMessage,
  logins: LoginThrottle,
): Promise<LoginResult> {
  const creds = basicCredentials(req.headers.authorization);
  if (!creds) return { ok: false, lockedMs: 0 };
  return logins.login(req.socket.remoteAddress ?? 'unknown', creds.name, creds.password);
}

/** Writing a robot's files is an operator's right (anyone in the anonymous local demo). */
export function operatorOnly(logins: LoginThrottle | null): Authorize {
  return async (req) => {
    if (!logins) return { ok: true };
    const who = await basicUser(req, logins);
    if (!who.ok) return { ok: false, status: 401, error: 'log in as an operator' };
    if (who.principal.role !== 'operator' && who.principal.role !== 'admin')
      return { ok: false, status: 403, error: `${who.principal.role}s may not change a robot` };
    return { ok: true };
  };
}

/** Any log-in, a viewer's included (anyone in the anonymous local demo). */
export function anyLogIn(logins: LoginThrottle | null): Authorize {
  return async (req) =>
    !logins || (await basicUser(req, logins)).ok
      ? { ok: true }
      : { ok: false, status: 401, error: 'log in' };
}

/**
 * HTTP Basic with a user's name and password (any role: a viewer may read the history) is
 * turned into the bearer token the middleware checks; anything else reaches it unchanged.
 */
export async function basicToBearer(
  req: http.IncomingMessage,
  logins: LoginThrottle,
  token: string,
): Promise<void> {
  if (!/^Basic /i.test(req.headers.authorization ?? '')) return;
  if ((await basicUser(req, logins)).ok) req.headers.authorization = `Bearer ${token}`;
  else delete req.headers.authorization;
}

/** `GET /api/whoami`, for the HUD (`whoamiAnswer`): the anonymous demo is an operator. */
export async function whoami(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  logins: LoginThrottle | null,
): Promise<void> {
  const a = whoamiAnswer(logins ? await basicUser(req, logins) : 'anonymous-demo');
  res.writeHead(a.status, a.headers).end(a.body);
}
