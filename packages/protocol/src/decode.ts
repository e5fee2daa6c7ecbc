import type { Frame } from './frames.ts';
import type { ReaderError } from './errors.ts';
import {
  KMS_CODE_MAX,
  KMS_COORD_MAX,
  ANGLE_DEG_MAX,
  MAX_FRAME_LENGTH,
  MOVE_MS_MAX,
  MV_MAX,
  PING_SEQ_MAX,
  PWM_MAX,
  PWM_MIN,
  SERVO_ID_ALL,
  TEMP_MAX,
} from './limits.ts';

/**
 * The regular expressions that clean the stream: one per frame syntax. Numeric fields
 * accept a few extra digits so that an out-of-range value is reported as such rather
 * than as "malformed"; the range checks below decide.
 */
const NUM = '(-?\\d{1,6}(?:\\.\\d{1,6})?)';
export const FRAME_PATTERNS = {
  move: /^#(\d{3})P(\d{1,5})T(\d{1,5})!$/,
  position: /^#(\d{3})P(\d{1,5})!$/,
  angleMove: /^#(\d{3})A([+-]?\d{1,6}(?:\.\d{1,6})?)T(\d{1,5})!$/,
  angle: /^#(\d{3})A([+-]?\d{1,6}(?:\.\d{1,6})?)!$/,
  readPosition: /^#(\d{3})PRAD!$/,
  readHealth: /^#(\d{3})PRTV!$/,
  stop: /^#(\d{3})PDST!$/,
  health: /^#(\d{3})T(\d{1,4})V(\d{1,6})!$/,
  kms: new RegExp(`^\\$KMS:${NUM},${NUM},${NUM}(?:,${NUM})?,(\\d{1,5}(?:\\.\\d{1,6})?)!$`),
  kmsResult: /^\$KMS:(\d{1,3})!$/,
  ping: /^\$PNG:(\d{1,11})!$/,
  time: /^\$TIM:(\d{1,16})!$/,
  controllerError: /^\$ERR:([^!]*)!$/,
} as const;

export type DecodeResult = { ok: true; frame: Frame } | { ok: false; error: ReaderError };

const fail = (
  kind: ReaderError['kind'],
  message: string,
  text: string,
): { ok: false; error: ReaderError } => ({
  ok: false,
  error: { kind, message, text: text.slice(0, MAX_FRAME_LENGTH) },
});

function rangeError(text: string, field: string, value: number, lo: number, hi: number) {
  return value < lo || value > hi
    ? fail('out-of-range', `${field} ${value} outside ${lo}–${hi}`, text)
    : null;
}

/** Decodes one complete frame text, `!` included. Never throws. */
export function decodeFrame(text: string): DecodeResult {
  if (text.length > MAX_FRAME_LENGTH) {
    return fail('too-long', `frame longer than ${MAX_FRAME_LENGTH} bytes`, text);
  }
  return text.charCodeAt(0) === 35 /* # */ ? decodeServoFrame(text) : decodeDollarFrame(text);
}

/** `text`'s characters [from, to) as a decimal integer, or -1 if one is not a digit. */
function digits(text: string, from: number, to: number): number {
  let v = 0;
  for (let i = from; i < to; i++) {
    const d = text.charCodeAt(i) - 48;
    if (d < 0 || d > 9) return -1;
    v = v * 10 + d;
  }
  return v;
}

/**
 * A position report (`#IIIPpppp!`, the bulk of every status stream) read without the regular
 * expression: exactly what FRAME_PATTERNS.position accepts, or -1 for "not this shape".
 */
function positionPwm(text: string): number {
  const n = text.length;
  if (n < 7 || n > 11 || text.charCodeAt(4) !== 80 /* P */ || text.charCodeAt(n - 1) !== 33)
    return -1;
  return digits(text, 5, n - 1);
}

/**
 * The two shapes of nearly every status message, `$TIM:ms!` and `#IIIPpppp!`, read in place from
 * `s`'s characters [from, to) (`!` included): no slice, no regular expression, no result object.
 * null for anything else, and for these shapes out of range, which decodeFrame then reports;
 * what it returns is exactly what decodeFrame returns for that text.
 */
export function decodeCommonFrame(s: string, from: number, to: number): Frame | null {
  const n = to - from;
  if (s.charCodeAt(to - 1) !== 33 /* ! */) return null;
  const c = s.charCodeAt(from);
  if (c === 35 /* # */) {
    if (n < 7 || n > 11 || s.charCodeAt(from + 4) !== 80 /* P */) return null;
    const id = digits(s, from + 1, from + 4);
    const pwm = digits(s, from + 5, to - 1);
    if (id < 0 || id > SERVO_ID_ALL - 1 || pwm < PWM_MIN || pwm > PWM_MAX) return null;
    return { type: 'position', id, pwm };
  }
  // `$TIM:` and up to 15 digits (exact as integers; FRAME_PATTERNS.time takes 16: the slow path)
  if (
    c !== 36 /* $ */ ||
    n < 7 ||
    n > 21 ||
    s.charCodeAt(from + 1) !== 84 /* T */ ||
    s.charCodeAt(from + 2) !== 73 /* I */ ||
    s.charCodeAt(from + 3) !== 77 /* M */ ||
    s.charCodeAt(from + 4) !== 58 /* : */
  )
    return null;
  const ms = digits(s, from + 5, to - 1);
  return ms < 0 ? null : { type: 'time', ms };
}

function decodeServoFrame(text: string): DecodeResult {
  let m: RegExpExecArray | null;
  const fastPwm = positionPwm(text);
  const fastId = fastPwm < 0 ? -1 : digits(text, 1, 4);
  if (fastId >= 0 || (m = FRAME_PATTERNS.position.exec(text))) {
    const id = fastId >= 0 ? fastId : Number(m![1]);
    const pwm = fastId >= 0 ? fastPwm : Number(m![2]);
    return (
      rangeError(text, 'id', id, 0, SERVO_ID_ALL - 1) ??
      rangeError(text, 'pwm', pwm, PWM_MIN, PWM_MAX) ?? {
        ok: true,
        frame: { type: 'position', id, pwm },
      }
    );
  }
  if ((m = FRAME_PATTERNS.move.exec(text))) {
    const id = Number(m[1]);
    const pwm = Number(m[2]);
    const ms = Number(m[3]);
    return (
      rangeError(text, 'id', id, 0, SERVO_ID_ALL) ??
      rangeError(text, 'pwm', pwm, PWM_MIN, PWM_MAX) ??
      rangeError(text, 'ms', ms, 0, MOVE_MS_MAX) ?? {
        ok: true,
        frame: { type: 'move', id, pwm, ms },
      }
    );
  }
  if ((m = FRAME_PATTERNS.angle.exec(text))) {
    const id = Number(m[1]);
    const deg = Number(m[2]);
    return (
      rangeError(text, 'id', id, 0, SERVO_ID_ALL - 1) ??
      rangeError(text, 'angle', deg, -ANGLE_DEG_MAX, ANGLE_DEG_MAX) ?? {
        ok: true,
        frame: { type: 'angle', id, deg: deg + 0 },
      }
    );
  }
  if ((m = FRAME_PATTERNS.angleMove.exec(text))) {
    const id = Number(m[1]);
    const deg = Number(m[2]);
    const ms = Number(m[3]);
    return (
      rangeError(text, 'id', id, 0, SERVO_ID_ALL) ??
      rangeError(text, 'angle', deg, -ANGLE_DEG_MAX, ANGLE_DEG_MAX) ??
      rangeError(text, 'ms', ms, 0, MOVE_MS_MAX) ?? {
        ok: true,
        frame: { type: 'angleMove', id, deg: deg + 0, ms },
      }
    );
  }
  if ((m = FRAME_PATTERNS.health.exec(text))) {
    const id = Number(m[1]);
    const temp = Number(m[2]);
    const mv = Number(m[3]);
    return (
      rangeError(text, 'id', id, 0, SERVO_ID_ALL - 1) ??
      rangeError(text, 'temperature', temp, 0, TEMP_MAX) ??
      rangeError(text, 'voltage', mv, 0, MV_MAX) ?? {
        ok: true,
        frame: { type: 'health', id, temp, mv },
      }
    );
  }
  for (const type of ['readPosition', 'readHealth', 'stop'] as const) {
    if ((m = FRAME_PATTERNS[type].exec(text))) {
      const id = Number(m[1]);
      return rangeError(text, 'id', id, 0, SERVO_ID_ALL) ?? { ok: true, frame: { type, id } };
    }
  }
  return fail('malformed', 'not a servo frame (#IIIP…, #IIIA…, #IIIT…V…)', text);
}

function decodeDollarFrame(text: string): DecodeResult {
  let m: RegExpExecArray | null;
  if ((m = FRAME_PATTERNS.time.exec(text))) {
    return { ok: true, frame: { type: 'time', ms: Number(m[1]) } };
  }
  if ((m = FRAME_PATTERNS.ping.exec(text))) {
    const seq = Number(m[1]);
    return (
      rangeError(text, 'ping sequence', seq, 0, PING_SEQ_MAX) ?? {
        ok: true,
        frame: { type: 'ping', seq },
      }
    );
  }
  if ((m = FRAME_PATTERNS.kmsResult.exec(text))) {
    const code = Number(m[1]);
    return (
      rangeError(text, 'IK code', code, 0, KMS_CODE_MAX) ?? {
        ok: true,
        frame: { type: 'kmsResult', code },
      }
    );
  }
  if ((m = FRAME_PATTERNS.kms.exec(text))) {
    const [x, y, z] = [Number(m[1]), Number(m[2]), Number(m[3])];
    const ms = Number(m[5]);
    const err =
      rangeError(text, 'x', x, -KMS_COORD_MAX, KMS_COORD_MAX) ??
      rangeError(text, 'y', y, -KMS_COORD_MAX, KMS_COORD_MAX) ??
      rangeError(text, 'z', z, -KMS_COORD_MAX, KMS_COORD_MAX) ??
      rangeError(text, 'ms', ms, 0, MOVE_MS_MAX);
    if (err) return err;
    if (m[4] === undefined) return { ok: true, frame: { type: 'kms', x, y, z, ms } };
    const alpha = Number(m[4]);
    return (
      rangeError(text, 'alpha', alpha, -180, 180) ?? {
        ok: true,
        frame: { type: 'kms', x, y, z, alpha, ms },
      }
    );
  }
  if ((m = FRAME_PATTERNS.controllerError.exec(text))) {
    return { ok: true, frame: { type: 'controllerError', text: m[1] ?? '' } };
  }
  return fail('malformed', 'not a $ frame ($KMS, $PNG, $TIM, $ERR)', text);
}
