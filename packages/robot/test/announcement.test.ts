/** The retained `arm/{id}/profile` message: what an arm writes, the page reads back. */
import { describe, expect, it } from 'vitest';
import {
  MAX_PROFILE_ANNOUNCEMENT_BYTES,
  parseAnnouncement,
  parseProfile,
  profileAnnouncement,
} from '../src/index.ts';
import { readModelFile } from './numeric-fixtures.ts';

describe('parseAnnouncement', () => {
  it('reads back the profile an arm announces', () => {
    const raw: unknown = JSON.parse(readModelFile('track6', 'profile.json'));
    const parsed = parseProfile(raw);
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const text = profileAnnouncement('track6', 't', raw);
    expect(JSON.parse(text)).toMatchObject({ name: 'track6', title: 't' });
    const r = parseAnnouncement(text);
    expect(r.ok && r.profile).toEqual(parsed.profile);
    expect(r.ok && r.profile.servos.length).toBe(7);
  });

  it('refuses what is not one, saying why', () => {
    expect(parseAnnouncement('{')).toEqual({
      ok: false,
      error: 'profile announcement is not JSON',
    });
    expect(parseAnnouncement('[]').ok).toBe(false);
    expect(parseAnnouncement('{"name":"x"}')).toEqual({
      ok: false,
      error: 'profile announcement has no "profile"',
    });
    const bad = parseAnnouncement(JSON.stringify({ profile: { format: 'nope' } }));
    expect(bad.ok).toBe(false);
    expect(!bad.ok && bad.error).toMatch(/^bad profile: /);
    expect(parseAnnouncement(' '.repeat(MAX_PROFILE_ANNOUNCEMENT_BYTES + 1))).toEqual({
      ok: false,
      error: `profile announcement over ${MAX_PROFILE_ANNOUNCEMENT_BYTES} bytes`,
    });
  });
});
