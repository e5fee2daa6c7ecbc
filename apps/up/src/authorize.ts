/**
 * Who may use `armtwin up`'s own routes, checked against the same log-ins as the broker (HTTP
 * Basic through its failed-log-in throttle, SECURITY.md); in the anonymous local demo
 * (`logins` null) anyone is an operator.
 */
import type http from 'node:http';
import { basicCredentials, type LoginResult, type LoginThrottle } from '@armtwin/auth';
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
