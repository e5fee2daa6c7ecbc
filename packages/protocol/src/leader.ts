/**
 * A leader arm's topics under the arm it drives (docs/protocol.md § A leader arm): its pose
 * (`$TIM` + a group of angle frames of the leader's servos, at its read rate), whether it drives
 * the arm (retained JSON `{following, reason}`, also its gateway's last will), and its user's
 * enable (`1`). Written by the leader gateway (`armtwin gateway --leader-of`), read by the HUD's
 * ghost. Pure: no I/O.
 */
import { CONTROL_USER_PATTERN } from './control-claims.ts';
import { assertArmId, isValidArmId } from './topics.ts';

/** The leader of `user` driving arm `armId`: its pose, state and enable topics. */
export function leaderTopics(armId: string, user: string) {
  if (!CONTROL_USER_PATTERN.test(user))
    throw new RangeError(`invalid user name ${JSON.stringify(user).slice(0, 40)}`);
  const pose = `arm/${assertArmId(armId)}/leader/${user}`;
  return { pose, state: `${pose}/state`, enable: `${pose}/enable` };
}

/** Every leader's pose of arm `armId` (a subscription filter). */
export const leaderPoseFilter = (armId: string) => `arm/${assertArmId(armId)}/leader/+`;
/** Every leader's state of arm `armId` (a subscription filter). */
export const leaderStateFilter = (armId: string) => `arm/${assertArmId(armId)}/leader/+/state`;

/** `arm/{id}/leader/{user}[/state|/enable]` → its parts, or null for any other topic. */
export function parseLeaderTopic(
  name: string,
): { armId: string; user: string; kind: 'pose' | 'state' | 'enable' } | null {
  const parts = name.split('/');
  if (parts.length < 4 || parts.length > 5 || parts[0] !== 'arm' || parts[2] !== 'leader')
    return null;
  const [, armId, , user, sub] = parts as [string, string, string, string, string | undefined];
  if (!isValidArmId(armId) || !CONTROL_USER_PATTERN.test(user)) return null;
  if (sub === undefined) return { armId, user, kind: 'pose' };
  return sub === 'state' || sub === 'enable' ? { armId, user, kind: sub } : null;
}

/** The retained state: whether the leader drives the arm, and why not. */
export interface LeaderState {
  following: boolean;
  reason: string;
}

const decoder = new TextDecoder();

/** The state in a payload, or an error message saying what was wrong with it. */
export function parseLeaderState(payload: Uint8Array | string): LeaderState | { error: string } {
  const text = typeof payload === 'string' ? payload : decoder.decode(payload);
  let v: unknown;
  try {
    v = JSON.parse(text);
  } catch {
    return { error: 'not JSON' };
  }
  const o = v as Partial<Record<keyof LeaderState, unknown>> | null;
  if (typeof o !== 'object' || o === null || typeof o.following !== 'boolean')
    return { error: 'no boolean "following"' };
  if (o.reason !== undefined && typeof o.reason !== 'string')
    return { error: '"reason" is not a string' };
  return { following: o.following, reason: (o.reason ?? '').slice(0, 500) };
}
