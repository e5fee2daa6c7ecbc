/**
 * The profile the HUD assumes when an arm announces none (an old arm, a real controller behind
 * `armtwin gateway`): armtwin5, the 5-axis arm of PROTOCOL.md §4. Bundled (not fetched), so the
 * store and the panels have a servo list from the first render.
 */
import { parseProfile, type Profile } from '@armtwin/robot';
import armtwin5 from '../../../../../public/models/armtwin5/profile.json';

export const DEFAULT_PROFILE_NAME = 'armtwin5';

function load(): Profile {
  const r = parseProfile(armtwin5);
  if (!r.ok) throw new Error(`bundled armtwin5 profile: ${r.errors.join('; ')}`);
  return r.profile;
}

export const DEFAULT_PROFILE: Profile = load();

/** How long the HUD waits for the selected arm's retained profile before assuming armtwin5, ms. */
export const PROFILE_WAIT_MS = 1000;
