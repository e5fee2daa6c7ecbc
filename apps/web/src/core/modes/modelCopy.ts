/**
 * The model copy's route on `armtwin up` (docs/protocol.md § Modes): `POST <api>/arms/{id}/model`
 * starts the copy of arm `{id}` (or puts a running one at the pose sent) at the real arm's last
 * reported pose, with the page's log-in. The answer, or the HTTP status and the server's words.
 */
import { authHeaders } from '../auth/whoami.ts';
import type { HudSettings } from '../config/settings.ts';

export type ModelCopyResult =
  { ok: true; armId: string; started: boolean } | { ok: false; error: string };

/** Servo id → pulse (µs) of every servo whose pulse is known; null when none is. */
export function poseBody(
  ids: readonly number[],
  pwm: ArrayLike<number>,
): Record<string, number> | null {
  const pulses: Record<string, number> = {};
  let any = false;
  ids.forEach((id, i) => {
    const p = pwm[i];
    if (p === undefined || !Number.isFinite(p)) return;
    pulses[String(id)] = Math.round(p);
    any = true;
  });
  return any ? pulses : null;
}

export async function startModelCopy(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password' | 'armId'>,
  pulses: Record<string, number> | null,
  fetchFn: typeof fetch = (url, init) => globalThis.fetch(url, init),
): Promise<ModelCopyResult> {
  try {
    const res = await fetchFn(
      `${settings.apiBase}/arms/${encodeURIComponent(settings.armId)}/model`,
      {
        method: 'POST',
        headers: { 'content-type': 'application/json', ...authHeaders(settings) },
        body: JSON.stringify(pulses ? { pulses } : {}),
        cache: 'no-store',
        credentials: 'omit',
      },
    );
    const body = (await res.json().catch(() => null)) as Record<string, unknown> | null;
    if (res.ok)
      return {
        ok: true,
        armId: typeof body?.armId === 'string' ? body.armId : '',
        started: body?.started === true,
      };
    const why =
      typeof body?.error === 'string'
        ? body.error
        : Array.isArray(body?.errors)
          ? body.errors.map(String).join('; ')
          : '';
    return { ok: false, error: `HTTP ${res.status}${why ? `: ${why}` : ''}` };
  } catch (err) {
    return { ok: false, error: err instanceof Error ? err.message : String(err) };
  }
}
