/**
 * `GET /api/whoami` (served by `armtwin up`): which user and role the credentials are. HTTP is
 * injected (`fetch`), parsing is pure. The broker enforces the role either way; the answer only
 * decides what the page offers.
 */
import type { WhoamiUser } from '@armtwin/api';
import { isRole, type Access } from './roles.ts';

export type Whoami =
  | { kind: 'user'; name: string; role: Access['role']; anonymous: boolean }
  /** 401: the server has users and these credentials (or none) are not one of them. */
  | { kind: 'unauthorized' }
  /** 429: too many failed log-ins from this address; the server checks nothing for `retryS`. */
  | { kind: 'locked'; retryS: number }
  /** No answer we can use: not served (404, a static server, Mosquitto only), network, junk. */
  | { kind: 'unavailable'; reason: string };

export type Fetch = (url: string, init: RequestInit) => Promise<Response>;

/** HTTP Basic for `username:password`, UTF-8 (what the server decodes). */
export function basicAuth(username: string, password: string): string {
  const bytes = new TextEncoder().encode(`${username}:${password}`);
  let bin = '';
  for (const b of bytes) bin += String.fromCharCode(b);
  return `Basic ${btoa(bin)}`;
}

/** The headers for `/api` requests: Basic when there is a user name, none otherwise. */
export function authHeaders(s: { username: string; password: string }): Record<string, string> {
  return s.username ? { authorization: basicAuth(s.username, s.password) } : {};
}

/** A response → Whoami (`retryAfter`: the Retry-After header of a 429). */
export function parseWhoami(status: number, body: unknown, retryAfter?: string | null): Whoami {
  if (status === 401) return { kind: 'unauthorized' };
  if (status === 429) {
    const s = Number(retryAfter);
    return { kind: 'locked', retryS: Number.isFinite(s) && s > 0 ? Math.ceil(s) : 60 };
  }
  if (status !== 200) return { kind: 'unavailable', reason: `HTTP ${status}` };
  const b = body as { [K in keyof WhoamiUser]?: unknown } | null;
  if (!b || typeof b !== 'object' || typeof b.name !== 'string' || !isRole(b.role))
    return { kind: 'unavailable', reason: 'not a whoami answer' };
  return { kind: 'user', name: b.name, role: b.role, anonymous: b.anonymous === true };
}

export async function fetchWhoami(
  apiBase: string,
  creds: { username: string; password: string },
  fetchFn: Fetch = (url, init) => globalThis.fetch(url, init),
  timeoutMs = 3000,
): Promise<Whoami> {
  try {
    const res = await fetchFn(`${apiBase}/whoami`, {
      headers: { accept: 'application/json', ...authHeaders(creds) },
      cache: 'no-store',
      credentials: 'omit',
      signal: AbortSignal.timeout(timeoutMs),
    });
    const body: unknown = res.status === 200 ? await res.json().catch(() => null) : null;
    return parseWhoami(res.status, body, res.headers.get('retry-after'));
  } catch (err) {
    return { kind: 'unavailable', reason: err instanceof Error ? err.message : String(err) };
  }
}

/**
 * The role the page acts on. whoami's answer wins; without one (unavailable, or a 401 from an
 * `/api` that does not know our broker's users, e.g. the middleware behind an API token in a
 * Mosquitto deployment), `?role=` (roleHint) says; without that, viewer ("default").
 */
export function resolveAccess(
  who: Whoami,
  roleHint: '' | 'viewer' | 'operator',
  username: string,
): Access {
  if (who.kind === 'user')
    return { role: who.role, source: who.anonymous ? 'demo' : 'server', name: who.name };
  if (roleHint) return { role: roleHint, source: 'hint', name: username };
  return { role: 'viewer', source: 'default', name: username };
}
