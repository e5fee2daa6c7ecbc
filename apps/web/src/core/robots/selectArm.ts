/**
 * Selecting an arm in the fleet list: the settings for it (saved like the Connection panel's),
 * and the page URL's `arm=` updated in place so a reload stays on that arm.
 */
import { isValidArmId } from '@armtwin/protocol';
import { saveSettings, type HudSettings } from '../config/settings.ts';

/** The query string with `arm` set to `armId` (other parameters kept). Pure. */
export function queryWithArm(search: string, armId: string): string {
  const q = new URLSearchParams(search);
  q.set('arm', armId);
  return `?${q.toString()}`;
}

/** New settings for `armId` (saved, URL updated), or null when it is invalid or already selected. */
export function settingsForArm(current: HudSettings, armId: string): HudSettings | null {
  if (!isValidArmId(armId) || armId === current.armId) return null;
  const next = { ...current, armId };
  saveSettings(next);
  const url = `${window.location.pathname}${queryWithArm(window.location.search, armId)}${window.location.hash}`;
  window.history.replaceState(window.history.state, '', url);
  return next;
}
