import type { Frame } from './frames.ts';
import { ProtocolError } from './errors.ts';
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

function checkInt(field: string, value: number, lo: number, hi: number): number {
  if (!Number.isInteger(value) || value < lo || value > hi) {
    throw new ProtocolError('out-of-range', `${field} ${value} must be an integer in ${lo}–${hi}`);
  }
  return value;
}

function checkNum(field: string, value: number, lo: number, hi: number): number {
  if (!Number.isFinite(value) || value < lo || value > hi) {
    throw new ProtocolError('out-of-range', `${field} ${value} must be a number in ${lo}–${hi}`);
  }
  return value;
}

const pad = (value: number, width: number) => String(value).padStart(width, '0');
const servoId = (id: number, allowAll = true) =>
  pad(checkInt('id', id, 0, allowAll ? SERVO_ID_ALL : SERVO_ID_ALL - 1), 3);

/** Decimal text without exponent, at most 3 decimals, no trailing zeros. */
function decimal(value: number): string {
  const text = value.toFixed(3).replace(/\.?0+$/, '');
  return text === '-0' ? '0' : text;
}

/**
 * `±ddd.dd`: an angle rounded half away from zero to two decimals (−0.004 → `+000.00`),
 * then checked against ±ANGLE_DEG_MAX, so a value that rounds out of range is refused.
 */
function angleText(deg: number): string {
  checkNum('angle', deg, -Infinity, Infinity);
  const hundredths = Math.sign(deg) * Math.round(Math.abs(deg) * 100);
  checkNum('angle', hundredths / 100, -ANGLE_DEG_MAX, ANGLE_DEG_MAX);
  const abs = Math.abs(hundredths);
  const sign = hundredths < 0 ? '-' : '+';
  return `${sign}${pad(Math.trunc(abs / 100), 3)}.${pad(abs % 100, 2)}`;
}

/** `#IIIA±ddd.ddTtttt!` (§8): servo `id` (255 = every servo) to `deg` degrees in `ms`. */
export const encodeAngleMove = (id: number, deg: number, ms: number) =>
  `#${servoId(id)}A${angleText(deg)}T${pad(checkInt('ms', ms, 0, MOVE_MS_MAX), 4)}!`;
/** `#IIIA±ddd.dd!` (§8): servo `id` is at `deg` degrees. */
export const encodeAngle = (id: number, deg: number) => `#${servoId(id, false)}A${angleText(deg)}!`;

export const encodeMove = (id: number, pwm: number, ms: number) =>
  `#${servoId(id)}P${pad(checkInt('pwm', pwm, PWM_MIN, PWM_MAX), 4)}T${pad(checkInt('ms', ms, 0, MOVE_MS_MAX), 4)}!`;
export const encodeReadPosition = (id: number) => `#${servoId(id)}PRAD!`;
export const encodeReadHealth = (id: number) => `#${servoId(id)}PRTV!`;
export const encodeStop = (id: number) => `#${servoId(id)}PDST!`;
/** `#255PDST!`: stop every servo now. */
export const EMERGENCY_STOP = '#255PDST!';

export function encodeKms(x: number, y: number, z: number, ms: number, alpha?: number): string {
  const coords = [x, y, z].map((v, i) => decimal(checkNum('xyz'[i]!, v, -KMS_COORD_MAX, KMS_COORD_MAX)));
  if (alpha !== undefined) coords.push(decimal(checkNum('alpha', alpha, -180, 180)));
  return `$KMS:${coords.join(',')},${checkInt('ms', ms, 0, MOVE_MS_MAX)}!`;
}

export const encodePing = (seq: number) => `$PNG:${checkInt('ping sequence', seq, 0, PING_SEQ_MAX)}!`;
export const encodePosition = (id: number, pwm: number) =>
  `#${servoId(id, false)}P${pad(checkInt('pwm', pwm, PWM_MIN, PWM_MAX), 4)}!`;
export const encodeHealth = (id: number, temp: number, mv: number) =>
  `#${servoId(id, false)}T${pad(checkInt('temperature', Math.round(temp), 0, TEMP_MAX), 3)}V${pad(checkInt('voltage', Math.round(mv), 0, MV_MAX), 4)}!`;
export const encodeKmsResult = (code: number) => `$KMS:${checkInt('IK code', code, 0, KMS_CODE_MAX)}!`;
export const encodeTime = (ms: number) => `$TIM:${checkInt('time', ms, 0, Number.MAX_SAFE_INTEGER)}!`;

/** `$ERR:text!`, with `!`, frame starts and control characters removed so the frame stays one frame. */
export function encodeControllerError(text: string): string {
  // eslint-disable-next-line no-control-regex -- control characters are exactly what is removed
  const clean = text.replace(/[!#${}\x00-\x1f\x7f-\uffff]/g, ' ').trim();
  return `$ERR:${clean.slice(0, MAX_FRAME_LENGTH - 6)}!`;
}

/** `{…}`: a group of already-encoded frames that start together. */
export const encodeGroup = (frames: readonly string[]) => `{${frames.join('')}}`;

/** Encodes any frame object (the inverse of decodeFrame). Throws ProtocolError when out of range. */
export function encodeFrame(frame: Frame): string {
  switch (frame.type) {
    case 'move':
      return encodeMove(frame.id, frame.pwm, frame.ms);
    case 'angleMove':
      return encodeAngleMove(frame.id, frame.deg, frame.ms);
    case 'readPosition':
      return encodeReadPosition(frame.id);
    case 'readHealth':
      return encodeReadHealth(frame.id);
    case 'stop':
      return encodeStop(frame.id);
    case 'kms':
      return encodeKms(frame.x, frame.y, frame.z, frame.ms, frame.alpha);
    case 'ping':
      return encodePing(frame.seq);
    case 'position':
      return encodePosition(frame.id, frame.pwm);
    case 'angle':
      return encodeAngle(frame.id, frame.deg);
    case 'health':
      return encodeHealth(frame.id, frame.temp, frame.mv);
    case 'kmsResult':
      return encodeKmsResult(frame.code);
    case 'time':
      return encodeTime(frame.ms);
    case 'controllerError':
      return encodeControllerError(frame.text);
  }
}
