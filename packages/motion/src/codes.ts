/**
 * Status codes of motion feedback. 0–8 are the analytic IK's (PROTOCOL.md §4 and armtwin's 8),
 * 2, 9, 10 the numeric IK's; 20–26 are the motion API's own.
 */
import { IK_CODES, NUMERIC_IK_CODES } from '@armtwin/ik';

export const MOTION_CODES = {
  ...IK_CODES,
  ...NUMERIC_IK_CODES,
  0: 'ok',
  20: 'invalid request',
  21: 'servo limit: a joint target is outside a servo’s limits',
  22: 'off the plan: pose checking gave up',
  23: 'stopped',
  24: 'below the floor: the tool or a joint would go under it',
  25: 'keep-out zone: a link would enter a zone of the profile',
  26: 'self-collision: two links of the arm would touch',
} as const;

export const CODE_OK = 0;
export const CODE_INVALID = 20;
export const CODE_SERVO_LIMIT = 21;
export const CODE_OFF_PLAN = 22;
export const CODE_STOPPED = 23;
export const CODE_BELOW_FLOOR = 24;
export const CODE_IN_ZONE = 25;
export const CODE_SELF_COLLISION = 26;

/** The words for a code (`code n` for one not listed). */
export function motionCodeMessage(code: number): string {
  return (MOTION_CODES as Record<number, string>)[code] ?? `code ${code}`;
}
