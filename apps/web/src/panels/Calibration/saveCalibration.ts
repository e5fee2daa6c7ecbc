/**
 * Sends a calibration to `armtwin up` (`PUT <api>/robots/<name>/calibration`, an operator's
 * right, answered by apps/up/src/calibration-route.ts), with the page's log-in. The server
 * writes the robot's profile.json (keeping a backup); the bus gateway running it takes the new
 * calibration at once and announces it, and the twin follows the announcement.
 */
import type { ServoCalibrationFields } from '@armtwin/ik';
import { authHeaders } from '../../auth/whoami.ts';
import type { HudSettings } from '../../config/settings.ts';

export type SaveResult = { ok: true; backup: string } | { ok: false; error: string };

export async function saveCalibration(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  robot: string,
  fields: ServoCalibrationFields,
  fetchFn: typeof fetch = (url, init) => globalThis.fetch(url, init),
): Promise<SaveResult> {
  try {
    const res = await fetchFn(
      `${settings.apiBase}/robots/${encodeURIComponent(robot)}/calibration`,
      {
        method: 'PUT',
        headers: { 'content-type': 'application/json', ...authHeaders(settings) },
        body: JSON.stringify({ servos: [fields] }),
        cache: 'no-store',
        credentials: 'omit',
      },
    );
    const body = (await res.json().catch(() => null)) as {
      backup?: unknown;
      errors?: unknown;
    } | null;
    if (res.ok && typeof body?.backup === 'string') return { ok: true, backup: body.backup };
    const errors = Array.isArray(body?.errors) ? body.errors.map(String) : [];
    return {
      ok: false,
      error: `HTTP ${res.status}${errors.length ? `: ${errors.join('; ')}` : ''}`,
    };
  } catch (err) {
    return { ok: false, error: `not saved: ${err instanceof Error ? err.message : String(err)}` };
  }
}
