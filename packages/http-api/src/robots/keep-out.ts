/**
 * `PUT /api/robots/<name>/keep-out` (an operator's right; anyone in the anonymous local demo):
 * the HUD's Zones section, `{"zones":[…], "linkRadius"?, "selfCollision"?}`, written as the
 * `keepOut` of `<models>/<name>/profile.json` (the first models folder holding it), checked by
 * the profile parser first (`applyKeepOut`: every problem named by zone and field) and written
 * with a backup of the old file (`replaceProfileFile`). The profile file is the one source of
 * truth: the simulator (zones-follow.ts), the bus gateway and the ROS 2 gateway
 * (profile-follow.ts) watch it, put the zones in force and announce the profile again, and the
 * pages take them from there.
 *
 * Answers JSON: 200 `{ok, keepOut, backup}`; 400 `{ok:false, errors}`; 401/403 for a missing or
 * non-operator log-in; 404 for an unknown robot; 413 for a body over
 * `MAX_KEEP_OUT_REQUEST_BYTES`.
 */
import { applyKeepOut, MAX_KEEP_OUT_REQUEST_BYTES } from '@armtwin/robot';
import { profileWriteRoute, type RobotWriteOptions } from './robot-write.ts';

export const keepOutRoute = (o: RobotWriteOptions) =>
  profileWriteRoute(o, {
    label: 'keep-out',
    maxBytes: MAX_KEEP_OUT_REQUEST_BYTES,
    request: (json) => ({ ok: true, value: json }),
    apply(raw, json) {
      const r = applyKeepOut(raw, json);
      return r.ok ? { ok: true, value: { raw: r.raw, told: { keepOut: r.keepOut } } } : r;
    },
    refusedAs: 'zones',
  });
