/**
 * The retained `arm/{id}/profile` message (docs/protocol.md, "Motion requests"):
 * `{"name","title","profile":{…profile.json…}}`, written by every arm that announces its profile
 * (the simulator, the bus and ROS 2 gateways) and read by the page as untrusted input. Pure.
 */
import { parseProfile } from './parse.ts';
import type { Profile } from './types.ts';

/**
 * Largest announcement, bytes: an arm refuses to publish a larger one and the page refuses to
 * read one; well under the broker's packet bound (64 KiB). track6's is about 3 KB.
 */
export const MAX_PROFILE_ANNOUNCEMENT_BYTES = 32768;

/** The announcement's payload for a profile's name and title and its profile.json as read. */
export const profileAnnouncement = (name: unknown, title: unknown, raw: unknown): string =>
  JSON.stringify({ name, title, profile: raw });

export type AnnouncementResult = { ok: true; profile: Profile } | { ok: false; error: string };

export function parseAnnouncement(text: string): AnnouncementResult {
  if (text.length > MAX_PROFILE_ANNOUNCEMENT_BYTES)
    return {
      ok: false,
      error: `profile announcement over ${MAX_PROFILE_ANNOUNCEMENT_BYTES} bytes`,
    };
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
