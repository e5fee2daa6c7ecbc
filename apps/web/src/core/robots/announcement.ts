/**
 * The retained `arm/{id}/profile` message (docs/protocol.md, "Motion requests"):
 * `{"name","title","profile":{…profile.json…}}`, read as untrusted input. Pure.
 */
import { parseProfile, type Profile } from '@armtwin/robot';

/** Largest announcement read, bytes (the arm refuses to publish one over 32 KiB). */
export const MAX_ANNOUNCEMENT_BYTES = 32768;

export type AnnouncementResult = { ok: true; profile: Profile } | { ok: false; error: string };

export function parseAnnouncement(text: string): AnnouncementResult {
  if (text.length > MAX_ANNOUNCEMENT_BYTES)
    return { ok: false, error: `profile announcement over ${MAX_ANNOUNCEMENT_BYTES} bytes` };
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch {
    return { ok: false, error: 'profile announcement is not JSON' };
  }
  if (typeof json !== 'object' || json === null || !('profile' in json))
    return { ok: false, error: 'profile announcement has no "profile"' };
  const r = parseProfile((json as { profile: unknown }).profile);
  if (!r.ok) return { ok: false, error: `bad profile: ${r.errors.slice(0, 3).join('; ')}` };
  return { ok: true, profile: r.profile };
}
