/**
 * A write to a robot's profile through `armtwin up` (`PUT <api>/robots/<name>/<what>`, an
 * operator's right: packages/http-api/src/robots/calibration.ts, keep-out.ts), with the page's log-in.
 * The answer's JSON on success; otherwise the HTTP status and every error the server named.
 */
import { authHeaders } from '../auth/whoami.ts';
import type { HudSettings } from '../config/settings.ts';

export type PutRobotResult =
  { ok: true; body: Record<string, unknown> } | { ok: false; error: string };

export async function putRobotFile(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  robot: string,
  what: 'calibration' | 'keep-out',
  payload: unknown,
  fetchFn: typeof fetch = (url, init) => globalThis.fetch(url, init),
): Promise<PutRobotResult> {
  try {
    const res = await fetchFn(`${settings.apiBase}/robots/${encodeURIComponent(robot)}/${what}`, {
      method: 'PUT',
      headers: { 'content-type': 'application/json', ...authHeaders(settings) },
      body: JSON.stringify(payload),
      cache: 'no-store',
      credentials: 'omit',
    });
    const body = (await res.json().catch(() => null)) as Record<string, unknown> | null;
    if (res.ok) return { ok: true, body: body ?? {} };
    const errors = Array.isArray(body?.errors) ? body.errors.map(String) : [];
    return {
      ok: false,
      error: `HTTP ${res.status}${errors.length ? `: ${errors.join('; ')}` : ''}`,
    };
  } catch (err) {
    return { ok: false, error: `not saved: ${err instanceof Error ? err.message : String(err)}` };
  }
}
