/**
 * `keepOut` of a profile (docs/robots.md, "Keep-out zones"): boxes, vertical cylinders and
 * half-space planes in the base frame, mm, plus the links' capsule radius. Every mistake is
 * reported with the zone's name and field (`keepOut.zones[1] "table".max: …`), so a zone file
 * with nonsense in it never loads: the profile is refused whole, and nothing moves on it.
 */
import { Fields, describe, type Json } from './fields.ts';
import { parseProfile } from './parse.ts';
import { ZONE_SHAPES, type ProfileKeepOut, type Zone } from './types.ts';

const ZONE_NAME = /^[A-Za-z0-9 _.-]{1,40}$/;
/** At most this many zones in one profile (each is checked against every link, per sample). */
export const MAX_ZONES = 64;

const KEYS: Record<Zone['shape'], readonly string[]> = {
  box: ['name', 'shape', 'min', 'max'],
  cylinder: ['name', 'shape', 'center', 'radius', 'zMin', 'zMax'],
  plane: ['name', 'shape', 'point', 'normal'],
};

function vec<N extends 2 | 3>(f: Fields, path: string, v: unknown, n: N): number[] | undefined {
  if (!Array.isArray(v) || v.length !== n)
    return f.fail(path, `must be [${n === 3 ? 'x, y, z' : 'x, y'}] in mm, got ${describe(v)}`);
  const out = v.map((x, i) => f.number(`${path}[${i}]`, x));
  return out.every((x) => x !== undefined) ? (out as number[]) : undefined;
}

function parseZone(f: Fields, path: string, raw: unknown): Zone | undefined {
  const o = f.object(path, raw);
  if (!o) return undefined;
  const name = f.string(
    `${path}.name`,
    o.name,
    ZONE_NAME,
    '1–40 letters, digits, spaces, _ . or -',
  );
  const at = name ? `${path} "${name}"` : path;
  const shape = f.oneOf(`${at}.shape`, o.shape, ZONE_SHAPES);
  if (!shape) return undefined;
  f.noUnknownKeys(at, o, KEYS[shape]);
  const before = f.errors.length;
  let zone: Zone | undefined;
  switch (shape) {
    case 'box': {
      const min = vec(f, `${at}.min`, o.min, 3);
      const max = vec(f, `${at}.max`, o.max, 3);
      if (min && max && min.some((v, i) => !(v < max[i]!)))
        f.fail(
          `${at}.max`,
          `must be above min on every axis, got min ${fmt(min)}, max ${fmt(max)}`,
        );
      else if (min && max) zone = { name: name!, shape, min: t3(min), max: t3(max) };
      break;
    }
    case 'cylinder': {
      const center = vec(f, `${at}.center`, o.center, 2);
      const radius = f.number(`${at}.radius`, o.radius, { positive: true });
      const zMin = f.number(`${at}.zMin`, o.zMin);
      const zMax = f.number(`${at}.zMax`, o.zMax);
      if (zMin !== undefined && zMax !== undefined && !(zMin < zMax))
        f.fail(`${at}.zMax`, `must be above zMin (${zMin}), got ${zMax}`);
      else if (center && radius !== undefined && zMin !== undefined && zMax !== undefined)
        zone = { name: name!, shape, center: [center[0]!, center[1]!], radius, zMin, zMax };
      break;
    }
    case 'plane': {
      const point = vec(f, `${at}.point`, o.point, 3);
      const normal = vec(f, `${at}.normal`, o.normal, 3);
      const len = normal ? Math.hypot(...normal) : 0;
      if (normal && !(len > 1e-9))
        f.fail(`${at}.normal`, 'must not be [0, 0, 0] (it points into the kept-out side)');
      else if (point && normal)
        zone = { name: name!, shape, point: t3(point), normal: t3(normal.map((v) => v / len)) };
      break;
    }
    default: {
      const never: never = shape;
      return never;
    }
  }
  return f.errors.length > before || !name ? undefined : zone;
}

/** Validate `keepOut`; undefined when absent (or broken, with errors recorded in `f`). */
export function parseKeepOut(f: Fields, raw: unknown): ProfileKeepOut | undefined {
  if (raw === undefined) return undefined;
  const o: Json | undefined = f.object('keepOut', raw);
  if (!o) return undefined;
  f.noUnknownKeys('keepOut', o, ['zones', 'linkRadius', 'selfCollision']);
  const linkRadius =
    o.linkRadius === undefined
      ? undefined
      : f.number('keepOut.linkRadius', o.linkRadius, { positive: true });
  let selfCollision: boolean | undefined;
  if (o.selfCollision !== undefined) {
    if (typeof o.selfCollision === 'boolean') selfCollision = o.selfCollision;
    else f.fail('keepOut.selfCollision', `must be true or false, got ${describe(o.selfCollision)}`);
  }
  const rawZones = o.zones === undefined ? [] : f.array('keepOut.zones', o.zones);
  if (rawZones && rawZones.length > MAX_ZONES)
    f.fail('keepOut.zones', `at most ${MAX_ZONES} zones, got ${rawZones.length}`);
  const zones: Zone[] = [];
  rawZones?.slice(0, MAX_ZONES).forEach((z, i) => {
    const zone = parseZone(f, `keepOut.zones[${i}]`, z);
    if (!zone) return;
    if (zones.some((y) => y.name === zone.name))
      f.fail(`keepOut.zones[${i}] "${zone.name}".name`, 'another zone has this name');
    else zones.push(zone);
  });
  return {
    zones,
    ...(linkRadius === undefined ? {} : { linkRadius }),
    ...(selfCollision === undefined ? {} : { selfCollision }),
  };
}

const t3 = (v: readonly number[]): [number, number, number] => [v[0]!, v[1]!, v[2]!];
const fmt = (v: readonly number[]) => `[${v.join(', ')}]`;

/** Largest keep-out request read, bytes (64 zones fit with room to spare). */
export const MAX_KEEP_OUT_REQUEST_BYTES = 16384;

export type ApplyKeepOutResult =
  { ok: true; raw: Json; keepOut: ProfileKeepOut } | { ok: false; errors: string[] };

/**
 * `raw`: profile.json as read; `keepOut`: the HUD's `{"zones": […], "linkRadius"?, …}`. The
 * new profile JSON (every other field as it was) only if `parseProfile` accepts it whole, else
 * every problem, each naming the zone and field. Pure.
 */
export function applyKeepOut(raw: unknown, keepOut: unknown): ApplyKeepOutResult {
  const before = parseProfile(raw);
  if (!before.ok) return { ok: false, errors: before.errors.map((e) => `profile.json: ${e}`) };
  const f = new Fields();
  const parsed = parseKeepOut(f, keepOut);
  if (f.errors.length || !parsed)
    return { ok: false, errors: f.errors.length ? f.errors : ['keepOut: missing'] };
  const next = { ...(raw as Json), keepOut } as Json;
  const after = parseProfile(next);
  if (!after.ok) return { ok: false, errors: after.errors };
  return { ok: true, raw: next, keepOut: after.profile.keepOut ?? parsed };
}
