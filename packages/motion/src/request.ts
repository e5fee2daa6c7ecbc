/**
 * Motion requests (`arm/{id}/request`, JSON): the shape, and a strict validator that names the
 * first bad field. Unknown fields, wrong types, non-finite or out-of-range numbers and
 * oversized arrays are refused. What needs the arm's profile (pose names, servo ids, limits,
 * reach) is checked when the request is planned (`planRequest`).
 */
import { KMS_COORD_MAX } from '@armtwin/protocol';
import type { MotionMode } from './plan.ts';

/** A tip target: mm, base frame; `pitch` in degrees from horizontal (−90 = down). */
export interface TipRequestTarget {
  x: number;
  y: number;
  z: number;
  pitch?: number;
}

/** Servo values by three-digit id, in `unit` (default `us`): like a profile's poses. */
export interface ServoRequestTarget {
  unit?: 'us' | 'servo' | 'joint';
  servos: Record<string, number>;
}

/** A named pose of the profile (`home`, `ready`, `open`, …), a tip target or servo values. */
export type RequestTarget = string | TipRequestTarget | ServoRequestTarget;

export interface MotionRequest {
  /** Chosen by the client, echoed in every feedback message: `[A-Za-z0-9._:-]{1,64}`. */
  id: string;
  mode: MotionMode;
  /** 1 … MAX_REQUEST_TARGETS targets, visited in order. */
  targets: RequestTarget[];
  /** Run the plan (true) or only plan it (false, the default). */
  execute?: boolean;
  /** Fraction of each servo's speed limit, (0, 1] (default 0.5). */
  speed?: number;
  /** Cartesian mode: tip speed, mm/s, (0, 5000] (default 100). */
  linearSpeed?: number;
}

export const MAX_REQUEST_TARGETS = 64;
export const MAX_REQUEST_SERVOS = 32;
/** Largest request payload read, bytes (a request with 64 targets fits in a few KB). */
export const MAX_REQUEST_BYTES = 16384;
export const REQUEST_ID_PATTERN = /^[A-Za-z0-9._:-]{1,64}$/;
const POSE_NAME = /^[a-z0-9_-]{1,32}$/;
const SERVO_KEY = /^\d{3}$/;

export type ValidateResult =
  | { ok: true; request: MotionRequest }
  | { ok: false; id: string | null; field: string; message: string };

class Invalid extends Error {
  constructor(
    readonly field: string,
    message: string,
  ) {
    super(`${field}: ${message}`);
  }
}

const isObject = (v: unknown): v is Record<string, unknown> =>
  typeof v === 'object' && v !== null && !Array.isArray(v);

function onlyKeys(path: string, o: Record<string, unknown>, allowed: readonly string[]): void {
  for (const k of Object.keys(o))
    if (!allowed.includes(k))
      throw new Invalid(
        path ? `${path}.${k}` : k,
        `unknown field (allowed: ${allowed.join(', ')})`,
      );
}

function num(path: string, v: unknown, min: number, max: number, exclusiveMin = false): number {
  if (typeof v !== 'number' || !Number.isFinite(v))
    throw new Invalid(path, 'expected a finite number');
  if (v > max || v < min || (exclusiveMin && v === min))
    throw new Invalid(path, `${v} is outside ${exclusiveMin ? '(' : '['}${min}, ${max}]`);
  return v;
}

function target(path: string, v: unknown): RequestTarget {
  if (typeof v === 'string') {
    if (!POSE_NAME.test(v)) throw new Invalid(path, 'a pose name is [a-z0-9_-]{1,32}');
    return v;
  }
  if (!isObject(v))
    throw new Invalid(path, 'expected a pose name, {x, y, z[, pitch]} or {unit, servos}');
  if ('servos' in v) {
    onlyKeys(path, v, ['unit', 'servos']);
    const out: ServoRequestTarget = { servos: {} };
    if (v.unit !== undefined) {
      if (v.unit !== 'us' && v.unit !== 'servo' && v.unit !== 'joint')
        throw new Invalid(`${path}.unit`, 'expected "us", "servo" or "joint"');
      out.unit = v.unit;
    }
    if (!isObject(v.servos))
      throw new Invalid(`${path}.servos`, 'expected an object {"001": value, …}');
    const keys = Object.keys(v.servos);
    if (keys.length === 0) throw new Invalid(`${path}.servos`, 'is empty');
    if (keys.length > MAX_REQUEST_SERVOS)
      throw new Invalid(`${path}.servos`, `more than ${MAX_REQUEST_SERVOS} servos`);
    for (const k of keys) {
      if (!SERVO_KEY.test(k) || Number(k) > 254)
        throw new Invalid(`${path}.servos.${k.slice(0, 8)}`, 'a servo id is three digits, 000–254');
      out.servos[k] = num(`${path}.servos.${k}`, v.servos[k], -KMS_COORD_MAX, KMS_COORD_MAX);
    }
    return out;
  }
  onlyKeys(path, v, ['x', 'y', 'z', 'pitch']);
  const t: TipRequestTarget = {
    x: num(`${path}.x`, v.x, -KMS_COORD_MAX, KMS_COORD_MAX),
    y: num(`${path}.y`, v.y, -KMS_COORD_MAX, KMS_COORD_MAX),
    z: num(`${path}.z`, v.z, -KMS_COORD_MAX, KMS_COORD_MAX),
  };
  if (v.pitch !== undefined) t.pitch = num(`${path}.pitch`, v.pitch, -180, 180);
  return t;
}

/** Validates parsed JSON as a request. The id is returned even when something else is wrong. */
export function validateRequest(json: unknown): ValidateResult {
  const id =
    isObject(json) && typeof json.id === 'string' && REQUEST_ID_PATTERN.test(json.id)
      ? json.id
      : null;
  try {
    if (!isObject(json)) throw new Invalid('(request)', 'expected a JSON object');
    onlyKeys('', json, ['id', 'mode', 'targets', 'execute', 'speed', 'linearSpeed']);
    if (id === null) throw new Invalid('id', 'required: a string matching [A-Za-z0-9._:-]{1,64}');
    if (json.mode !== 'joint' && json.mode !== 'cartesian')
      throw new Invalid('mode', 'expected "joint" or "cartesian"');
    if (!Array.isArray(json.targets)) throw new Invalid('targets', 'expected an array');
    if (json.targets.length === 0) throw new Invalid('targets', 'is empty');
    if (json.targets.length > MAX_REQUEST_TARGETS)
      throw new Invalid(
        'targets',
        `${json.targets.length} targets; at most ${MAX_REQUEST_TARGETS}`,
      );
    const request: MotionRequest = {
      id,
      mode: json.mode,
      targets: json.targets.map((t, i) => target(`targets[${i}]`, t)),
    };
    if (json.execute !== undefined) {
      if (typeof json.execute !== 'boolean') throw new Invalid('execute', 'expected true or false');
      request.execute = json.execute;
    }
    if (json.speed !== undefined) request.speed = num('speed', json.speed, 0, 1, true);
    if (json.linearSpeed !== undefined)
      request.linearSpeed = num('linearSpeed', json.linearSpeed, 0, 5000, true);
    return { ok: true, request };
  } catch (err) {
    if (!(err instanceof Invalid)) throw err;
    return { ok: false, id, field: err.field, message: err.message };
  }
}

/** Parses and validates a request payload (bytes or text): size, JSON, shape. */
export function parseRequest(payload: string | Uint8Array): ValidateResult {
  if (payload.length > MAX_REQUEST_BYTES)
    return {
      ok: false,
      id: null,
      field: '(request)',
      message: `(request): ${payload.length} bytes; at most ${MAX_REQUEST_BYTES}`,
    };
  const text = typeof payload === 'string' ? payload : new TextDecoder().decode(payload);
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch {
    return { ok: false, id: null, field: '(request)', message: '(request): not JSON' };
  }
  return validateRequest(json);
}
