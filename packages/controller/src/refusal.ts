/**
 * What the controller refuses before it runs a frame: a servo it does not have, a move past a
 * joint's limit (pulse frames against the pulse range, §8 angle frames in servo degrees), a
 * report frame sent to it. The keep-out rules (floor, zones) come after, in the core. Pure: the
 * core counts each refusal by its kind.
 */
import {
  SERVO_ID_ALL,
  unhandled,
  type AngleMoveFrame,
  type Frame,
  type MoveFrame,
} from '@armtwin/protocol';
import { id3, jointIndex, type Joint } from './joints.ts';

/** Every kind of refusal the controller counts. */
export const REFUSAL_KINDS = [
  'limit',
  'floor',
  'zone',
  'unknown-servo',
  'group',
  'unexpected',
  'ik',
  'not-ready',
  'no-reading',
  'kms',
] as const;
export type RefusalKind = (typeof REFUSAL_KINDS)[number];

export interface Refusal {
  kind: RefusalKind;
  reason: string;
}

/** Limits are exact within this much (pulses and degrees computed through a profile). */
const TOLERANCE = 1e-9;

function unknownServo(id: number, joints: readonly Joint[]): Refusal | null {
  return id !== SERVO_ID_ALL && jointIndex(joints, id) < 0
    ? { kind: 'unknown-servo', reason: `no servo ${id3(id)}` }
    : null;
}

/** Why `frame` cannot run on these joints, or null when it can. */
export function frameRefusal(frame: Frame, joints: readonly Joint[]): Refusal | null {
  switch (frame.type) {
    case 'move':
      return moveRefusal(frame, joints);
    case 'angleMove':
      return angleMoveRefusal(frame, joints);
    case 'readPosition':
    case 'readHealth':
    case 'stop':
      return unknownServo(frame.id, joints);
    case 'kms':
    case 'ping':
    case 'time':
      return null;
    case 'position':
    case 'angle':
    case 'health':
    case 'kmsResult':
    case 'controllerError':
      return { kind: 'unexpected', reason: `unexpected ${frame.type} frame on control` };
    default:
      return unhandled(frame);
  }
}

/** Whether pulse `pwm` is within joint j's pulse range. */
export const pulseWithin = (j: Joint, pwm: number) =>
  Number.isFinite(pwm) && pwm >= j.minPwm - TOLERANCE && pwm <= j.maxPwm + TOLERANCE;

function moveRefusal(m: MoveFrame, joints: readonly Joint[]): Refusal | null {
  const unknown = unknownServo(m.id, joints);
  if (unknown) return unknown;
  for (const j of joints)
    if ((m.id === SERVO_ID_ALL || m.id === j.id) && !pulseWithin(j, m.pwm))
      return {
        kind: 'limit',
        reason: `limit ${id3(j.id)} P${m.pwm} outside ${j.minPwm}-${j.maxPwm}`,
      };
  return null;
}

/** `#IIIA±ddd.ddTtttt!`: checked in servo degrees against the joint's limits. */
function angleMoveRefusal(m: AngleMoveFrame, joints: readonly Joint[]): Refusal | null {
  const unknown = unknownServo(m.id, joints);
  if (unknown) return unknown;
  for (const j of joints)
    if (
      (m.id === SERVO_ID_ALL || m.id === j.id) &&
      !(m.deg >= j.minDeg - TOLERANCE && m.deg <= j.maxDeg + TOLERANCE)
    )
      return {
        kind: 'limit',
        reason: `limit ${id3(j.id)} A${m.deg} outside ${j.minDeg}..${j.maxDeg}`,
      };
  return null;
}
