/**
 * What the simulated controller refuses before it runs a frame: a servo it does not have, a
 * move past a joint's limit (pulse frames against the profile's pulse range, §8 angle frames in
 * servo degrees), a report frame sent to it. The keep-out rules (floor, zones) come after, in
 * the model. Pure: the model counts each refusal by its kind.
 */
import { isWithinLimits, type ArmProfile } from '@armtwin/ik';
import {
  SERVO_ID_ALL,
  unhandled,
  type AngleMoveFrame,
  type Frame,
  type MoveFrame,
} from '@armtwin/protocol';
import type { Servos } from './servos.ts';

export const id3 = (id: number) => String(id).padStart(3, '0');

export interface Refusal {
  kind: 'limit' | 'unknown-servo' | 'unexpected';
  reason: string;
}

function unknownServo(id: number, s: Servos): Refusal | null {
  return id !== SERVO_ID_ALL && s.indexOf(id) < 0
    ? { kind: 'unknown-servo', reason: `no servo ${id3(id)}` }
    : null;
}

/** Why `frame` cannot run on these servos, or null when it can. */
export function frameRefusal(frame: Frame, s: Servos, arm: ArmProfile): Refusal | null {
  switch (frame.type) {
    case 'move':
      return moveRefusal(frame, s, arm);
    case 'angleMove':
      return angleMoveRefusal(frame, s, arm);
    case 'readPosition':
    case 'readHealth':
    case 'stop':
      return unknownServo(frame.id, s);
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

function moveRefusal(m: MoveFrame, s: Servos, arm: ArmProfile): Refusal | null {
  const unknown = unknownServo(m.id, s);
  if (unknown) return unknown;
  for (let i = 0; i < s.count; i++) {
    const id = s.ids[i]!;
    if ((m.id === SERVO_ID_ALL || m.id === id) && !isWithinLimits(id, m.pwm, arm))
      return {
        kind: 'limit',
        reason: `limit ${id3(id)} P${m.pwm} outside ${s.minPwm[i]}-${s.maxPwm[i]}`,
      };
  }
  return null;
}

/** `#IIIA±ddd.ddTtttt!`: checked in servo degrees against the profile's limits. */
function angleMoveRefusal(m: AngleMoveFrame, s: Servos, arm: ArmProfile): Refusal | null {
  const unknown = unknownServo(m.id, s);
  if (unknown) return unknown;
  for (let i = 0; i < s.count; i++) {
    const spec = arm.servos[i]!;
    if (
      (m.id === SERVO_ID_ALL || m.id === spec.id) &&
      !(m.deg >= spec.minDeg && m.deg <= spec.maxDeg)
    )
      return {
        kind: 'limit',
        reason: `limit ${id3(spec.id)} A${m.deg} outside ${spec.minDeg}..${spec.maxDeg}`,
      };
  }
  return null;
}
