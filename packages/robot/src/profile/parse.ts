/**
 * `parseProfile`: validate a robot profile's parsed JSON (`public/models/<name>/profile.json`)
 * and return it typed, or every problem found, each message naming its field. Pure: the caller
 * reads the file and runs `JSON.parse`. The format is described in docs/robots.md.
 */
import { ANGLE_DEG_MAX, PWM_MAX, PWM_MIN, SERVO_ID_MAX } from '@armtwin/protocol';
import { pwmFromServo, servoFromPwm, servoWithinLimits, pwmWithinLimits } from './convert.ts';
import { Fields, type Json } from './fields.ts';
import { parseKeepOut } from './keep-out.ts';
import {
  PROFILE_FORMAT,
  PROFILE_SERVO_DEFAULTS as D,
  SERVO_UNITS,
  type Analytic5Spec,
  type ParseProfileResult,
  type ProfileIk,
  type ProfileServo,
} from './types.ts';

const NAME = /^[a-z0-9_-]{1,32}$/;
const NAME_WHAT = '1–32 characters of a–z, 0–9, _ or -';
const SERVO_KEYS = [
  'id',
  'name',
  'joint',
  'type',
  'units',
  'polarity',
  'offset',
  'pulseMin',
  'pulseMax',
  'min',
  'max',
  'maxSpeed',
];

function servoKey(id: number): string {
  return String(id).padStart(3, '0');
}

function parseId(f: Fields, path: string, v: unknown): number | undefined {
  if (typeof v === 'string' && /^\d{3}$/.test(v) && Number(v) <= SERVO_ID_MAX) return Number(v);
  if (typeof v === 'number' && Number.isInteger(v) && v >= 0 && v <= SERVO_ID_MAX) return v;
  return f.fail(path, `must be a servo id "000"–"254" (or 0–254), got ${JSON.stringify(v)}`);
}

function parseServo(f: Fields, path: string, raw: unknown): ProfileServo | undefined {
  const o = f.object(path, raw);
  if (!o) return undefined;
  f.noUnknownKeys(path, o, SERVO_KEYS);
  const before = f.errors.length;
  const id = parseId(f, `${path}.id`, o.id);
  const name = f.string(`${path}.name`, o.name);
  const joint = f.string(`${path}.joint`, o.joint);
  const type = f.oneOf(`${path}.type`, o.type, ['revolute', 'prismatic'] as const);
  const units = f.oneOf(`${path}.units`, o.units, SERVO_UNITS, D.units);
  const polarity = f.oneOf(`${path}.polarity`, o.polarity, [1, -1] as const, D.polarity);
  const offset = f.number(`${path}.offset`, o.offset, { fallback: D.offset });
  const pulseMin = f.number(`${path}.pulseMin`, o.pulseMin, {
    integer: true,
    fallback: D.pulseMin,
  });
  const pulseMax = f.number(`${path}.pulseMax`, o.pulseMax, {
    integer: true,
    fallback: D.pulseMax,
  });
  const min = f.number(`${path}.min`, o.min);
  const max = f.number(`${path}.max`, o.max);
  const maxSpeed = f.number(`${path}.maxSpeed`, o.maxSpeed, { positive: true });
  if (f.errors.length > before) return undefined;
  const s = {
    id,
    key: servoKey(id!),
    name,
    joint,
    type,
    units,
    polarity,
    offset,
    pulseMin,
    pulseMax,
    min,
    max,
    maxSpeed,
  } as ProfileServo;
  if (s.pulseMin < PWM_MIN || s.pulseMax > PWM_MAX || s.pulseMin >= s.pulseMax)
    return f.fail(
      `${path}.pulseMin`,
      `pulse range must satisfy ${PWM_MIN} ≤ pulseMin < pulseMax ≤ ${PWM_MAX}, got ${s.pulseMin}–${s.pulseMax}`,
    );
  if (s.min >= s.max)
    return f.fail(`${path}.min`, `must be less than max (${s.max}), got ${s.min}`);
  if (s.type === 'prismatic' && s.offset !== 0)
    return f.fail(
      `${path}.offset`,
      'must be 0 (or absent) on a prismatic axis: its pulse range maps onto min…max',
    );
  if (s.units === 'angle') {
    if (s.type !== 'revolute')
      return f.fail(
        `${path}.units`,
        '"angle" is for revolute servos only (angle frames carry degrees)',
      );
    const lo = s.min - s.offset;
    const hi = s.max - s.offset;
    if (lo < -ANGLE_DEG_MAX || hi > ANGLE_DEG_MAX)
      return f.fail(
        `${path}.min`,
        `limits ${s.min}…${s.max}° (offset ${s.offset}°) are servo angles ${lo}…${hi}°, outside what an angle frame carries (±${ANGLE_DEG_MAX}°)`,
      );
  } else if (s.type === 'revolute') {
    const a = pwmFromServo(s, s.min - s.offset);
    const b = pwmFromServo(s, s.max - s.offset);
    if (Math.min(a, b) < s.pulseMin || Math.max(a, b) > s.pulseMax)
      return f.fail(
        `${path}.min`,
        `limits ${s.min}…${s.max}° (offset ${s.offset}°) need pulses ${Math.min(a, b)}–${Math.max(a, b)} µs, outside the pulse range ${s.pulseMin}–${s.pulseMax}`,
      );
  }
  return s;
}

function parseIk(f: Fields, raw: unknown, servos: readonly ProfileServo[]): ProfileIk | undefined {
  const o = f.object('ik', raw);
  if (!o) return undefined;
  f.noUnknownKeys('ik', o, ['kind', 'baseLink', 'tipLink', 'analytic5', 'floorZ']);
  const kind = f.oneOf('ik.kind', o.kind, ['analytic5', 'numeric'] as const);
  const baseLink = f.string('ik.baseLink', o.baseLink);
  const tipLink = f.string('ik.tipLink', o.tipLink);
  // The floor (keep-out below it), mm in the base frame; absent = the default of @armtwin/motion.
  const floorZ = o.floorZ === undefined ? undefined : f.number('ik.floorZ', o.floorZ);
  const floor = floorZ === undefined ? {} : { floorZ };
  if (kind !== 'analytic5') {
    if (o.analytic5 !== undefined)
      f.fail('ik.analytic5', 'only allowed when ik.kind is "analytic5"');
    return kind && baseLink && tipLink ? { kind, baseLink, tipLink, ...floor } : undefined;
  }
  const a = f.object('ik.analytic5', o.analytic5);
  if (!a) return undefined;
  f.noUnknownKeys('ik.analytic5', a, ['links', 'jointOffsetsDeg']);
  const links = f.object('ik.analytic5.links', a.links);
  const l =
    links &&
    (['l0', 'l1', 'l2', 'l3'] as const).map((k) =>
      f.number(`ik.analytic5.links.${k}`, links[k], { positive: true }),
    );
  if (links) f.noUnknownKeys('ik.analytic5.links', links, ['l0', 'l1', 'l2', 'l3']);
  const offs = f.array('ik.analytic5.jointOffsetsDeg', a.jointOffsetsDeg);
  if (offs && offs.length !== 4)
    f.fail(
      'ik.analytic5.jointOffsetsDeg',
      `must hold 4 numbers (servos 000–003), got ${offs.length}`,
    );
  const o4 = offs?.map((v, i) => f.number(`ik.analytic5.jointOffsetsDeg[${i}]`, v));
  if (servos.length < 4 || servos.slice(0, 4).some((s) => s.type !== 'revolute'))
    f.fail(
      'servos',
      'ik.kind "analytic5" needs at least 4 servos, the first 4 revolute (base, shoulder, elbow, wrist pitch)',
    );
  if (
    !kind ||
    !baseLink ||
    !tipLink ||
    !l ||
    l.some((v) => v === undefined) ||
    !o4 ||
    o4.length !== 4 ||
    o4.some((v) => v === undefined)
  )
    return undefined;
  const analytic5: Analytic5Spec = {
    links: { l0: l[0]!, l1: l[1]!, l2: l[2]!, l3: l[3]! },
    jointOffsetsDeg: o4 as unknown as [number, number, number, number],
  };
  return { kind, baseLink, tipLink, analytic5, ...floor };
}

/** One pose → servo values in servo order (NaN where absent). */
function parsePose(
  f: Fields,
  path: string,
  raw: unknown,
  servos: readonly ProfileServo[],
  broken: ReadonlySet<string>,
): number[] | undefined {
  const o = f.object(path, raw);
  if (!o) return undefined;
  f.noUnknownKeys(path, o, ['unit', 'servos']);
  const unit = f.oneOf(`${path}.unit`, o.unit, ['us', 'servo', 'joint'] as const);
  const values = f.object(`${path}.servos`, o.servos);
  if (!unit || !values) return undefined;
  const out = servos.map(() => NaN);
  for (const [key, v] of Object.entries(values)) {
    const i = servos.findIndex((s) => s.key === key);
    const p = `${path}.servos.${key}`;
    if (i < 0) {
      if (broken.has(key)) continue; // that servo's own error is already reported
      f.fail(p, `no servo with id "${key}" (ids are ${servos.map((s) => s.key).join(', ')})`);
      continue;
    }
    const s = servos[i]!;
    const n = f.number(p, v);
    if (n === undefined) continue;
    const value = unit === 'us' ? servoFromPwm(s, n) : unit === 'joint' ? n - s.offset : n;
    const ok = unit === 'us' ? pwmWithinLimits(s, n) : servoWithinLimits(s, value);
    if (!ok)
      f.fail(
        p,
        `${n} ${unit === 'us' ? 'µs' : s.type === 'revolute' ? '°' : 'mm'} is outside the servo's limits`,
      );
    out[i] = value;
  }
  return out;
}

/** Validate a profile's parsed JSON. Never throws. */
export function parseProfile(json: unknown): ParseProfileResult {
  const f = new Fields();
  const o = f.object('profile', json);
  if (!o) return { ok: false, errors: f.errors };
  f.noUnknownKeys('', o, ['format', 'name', 'title', 'urdf', 'ik', 'servos', 'poses', 'keepOut']);
  if (o.format !== PROFILE_FORMAT)
    f.fail('format', `must be "${PROFILE_FORMAT}", got ${JSON.stringify(o.format)}`);
  const name = f.string('name', o.name, NAME, NAME_WHAT);
  const title = o.title === undefined ? name : f.string('title', o.title);
  const urdf = f.string(
    'urdf',
    o.urdf,
    /^[^/\\]+\.urdf$/,
    "a file name ending in .urdf, in the profile's folder",
  );
  const rawServos = f.array('servos', o.servos);
  if (rawServos && rawServos.length === 0) f.fail('servos', 'must list at least one servo');
  const servos: ProfileServo[] = [];
  const broken = new Set<string>();
  rawServos?.forEach((raw, i) => {
    const s = parseServo(f, `servos[${i}]`, raw);
    if (!s) {
      const id = (raw as Json | null)?.id;
      if (typeof id === 'string' || typeof id === 'number') broken.add(String(id).padStart(3, '0'));
      return;
    }
    if (servos.some((t) => t.id === s.id))
      f.fail(`servos[${i}].id`, `duplicate servo id "${s.key}"`);
    else if (servos.some((t) => t.joint === s.joint))
      f.fail(`servos[${i}].joint`, `joint "${s.joint}" is already driven by another servo`);
    else servos.push(s);
  });
  const ik = parseIk(f, o.ik, servos);
  const poses: Record<string, number[]> = {};
  const rawPoses = f.object('poses', o.poses);
  if (rawPoses) {
    for (const [poseName, raw] of Object.entries(rawPoses)) {
      if (poseName.startsWith('$')) continue;
      if (!NAME.test(poseName)) f.fail(`poses.${poseName}`, `pose names must be ${NAME_WHAT}`);
      const pose = parsePose(f, `poses.${poseName}`, raw, servos, broken);
      if (pose) poses[poseName] = pose;
    }
    if (!('home' in rawPoses)) f.fail('poses.home', 'is required (the pose the arm starts in)');
    else if (poses.home?.some((v, i) => Number.isNaN(v) && !broken.has(servos[i]!.key)))
      f.fail(
        'poses.home',
        `must give every servo (missing ${servos
          .filter((_, i) => Number.isNaN(poses.home![i]))
          .map((s) => s.key)
          .join(', ')})`,
      );
  }
  const keepOut = parseKeepOut(f, o.keepOut);
  if (f.errors.length > 0) return { ok: false, errors: f.errors };
  const profile = { name: name!, title: title!, urdf: urdf!, ik: ik!, servos, poses };
  return { ok: true, profile: keepOut ? { ...profile, keepOut } : profile };
}
