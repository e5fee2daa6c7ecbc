/**
 * Sends a robot's keep-out zones to `armtwin up` (`PUT <api>/robots/<name>/keep-out`, an
 * operator's right, answered by apps/up/src/keep-out-route.ts), with the page's log-in. The
 * server checks them (every problem named by zone and field) and writes them into the robot's
 * profile.json; the simulator and the bus gateway take them from the file at once and announce
 * the profile again, and this page draws and checks them from that announcement.
 */
import type { ProfileKeepOut } from '@armtwin/ik';
import { authHeaders } from '../../auth/whoami.ts';
import type { HudSettings } from '../../config/settings.ts';

export type SaveKeepOutResult = { ok: true } | { ok: false; error: string };

export async function saveKeepOut(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  robot: string,
  keepOut: ProfileKeepOut,
  fetchFn: typeof fetch = (url, init) => globalThis.fetch(url, init),
): Promise<SaveKeepOutResult> {
  try {
    const res = await fetchFn(`${settings.apiBase}/robots/${encodeURIComponent(robot)}/keep-out`, {
      method: 'PUT',
      headers: { 'content-type': 'application/json', ...authHeaders(settings) },
      body: JSON.stringify(keepOut),
      cache: 'no-store',
      credentials: 'omit',
    });
    const body = (await res.json().catch(() => null)) as { errors?: unknown } | null;
    if (res.ok) return { ok: true };
    const errors = Array.isArray(body?.errors) ? body.errors.map(String) : [];
    return {
      ok: false,
      error: `HTTP ${res.status}${errors.length ? `: ${errors.join('; ')}` : ''}`,
    };
  } catch (err) {
    return { ok: false, error: `not saved: ${err instanceof Error ? err.message : String(err)}` };
  }
}
