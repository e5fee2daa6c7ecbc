/**
 * Writing a calibration into a profile (pure): `parseCalibrationRequest` checks what the HUD
 * sends (`{"servos":[{"id","polarity","offset","min","max"}]}`), `applyCalibration` sets those
 * fields on the servos of profile.json as it was read, keeps every other field as it was, and
 * returns the new JSON only if `parseProfile` accepts it. Named poses keep their joint-space
 * meaning: each is rewritten in joint units (`"unit": "joint"`), the calibrated joints clamped
 * into their new limits.
 */
import type { ServoCalibrationFields } from './calibration.ts';
import { Fields, type Json } from './fields.ts';
import { parseProfile } from './parse.ts';
import type { Profile } from './types.ts';

/** Largest calibration request read, bytes. */
export const MAX_CALIBRATION_REQUEST_BYTES = 16384;

export type CalibrationRequestResult =
  { ok: true; servos: ServoCalibrationFields[] } | { ok: false; errors: string[] };

export function parseCalibrationRequest(json: unknown): CalibrationRequestResult {
  const f = new Fields();
  const o = f.object('calibration', json);
  const list = o && f.array('servos', o.servos);
  if (o) f.noUnknownKeys('', o, ['servos']);
  if (list && list.length === 0) f.fail('servos', 'must list at least one servo');
  const servos: ServoCalibrationFields[] = [];
  list?.forEach((raw, i) => {
    const p = `servos[${i}]`;
    const s = f.object(p, raw);
    if (!s) return;
    f.noUnknownKeys(p, s, ['id', 'polarity', 'offset', 'min', 'max']);
    const id = f.number(`${p}.id`, s.id, { integer: true });
    const polarity = f.oneOf(`${p}.polarity`, s.polarity, [1, -1] as const);
    const offset = f.number(`${p}.offset`, s.offset);
    const min = f.number(`${p}.min`, s.min);
    const max = f.number(`${p}.max`, s.max);
    if (id === undefined || !polarity || offset === undefined) return;
    if (min === undefined || max === undefined) return;
    if (servos.some((t) => t.id === id)) f.fail(`${p}.id`, `servo ${id} is listed twice`);
    else servos.push({ id, polarity, offset, min, max });
  });
  return f.errors.length ? { ok: false, errors: f.errors } : { ok: true, servos };
}

export type ApplyCalibrationResult =
  { ok: true; raw: Json; profile: Profile } | { ok: false; errors: string[] };

const round2 = (v: number) => Math.round(v * 100) / 100 + 0;
const idOf = (v: unknown) => (typeof v === 'string' ? Number(v) : v);

/** `raw`: profile.json as read; `servos`: the fields to set (`parseCalibrationRequest`). */
export function applyCalibration(
  raw: unknown,
  servos: readonly ServoCalibrationFields[],
): ApplyCalibrationResult {
  const before = parseProfile(raw);
  if (!before.ok) return { ok: false, errors: before.errors.map((e) => `profile.json: ${e}`) };
  const old = before.profile;
  const next = structuredClone(raw) as Json;
  const rawServos = next.servos as Json[];
  const errors: string[] = [];
  for (const c of servos) {
    const k = old.servos.findIndex((s) => s.id === c.id);
    const servo = old.servos[k];
    if (!servo) {
      errors.push(`servos: no servo with id ${c.id} in profile ${old.name}`);
      continue;
    }
    if (servo.units !== 'angle' || servo.type !== 'revolute') {
      errors.push(`servo ${servo.key}: only bus servos (units "angle") are calibrated`);
      continue;
    }
    const entry = rawServos.find((s) => idOf(s.id) === c.id)!;
    Object.assign(entry, { polarity: c.polarity, offset: c.offset, min: c.min, max: c.max });
  }
  if (errors.length) return { ok: false, errors };
  const poses: Json = {};
  for (const [name, values] of Object.entries(old.poses)) {
    const joint: Record<string, number> = {};
    old.servos.forEach((s, i) => {
      const v = values[i]!;
      if (Number.isNaN(v)) return;
      let j = s.type === 'revolute' ? v + s.offset : v;
      const c = servos.find((t) => t.id === s.id);
      if (c) j = Math.min(c.max, Math.max(c.min, j));
      joint[s.key] = round2(j);
    });
    poses[name] = { unit: 'joint', servos: joint };
  }
  const comments = Object.entries((next.poses as Json | undefined) ?? {}).filter(([k]) =>
    k.startsWith('$'),
  );
  next.poses = { ...Object.fromEntries(comments), ...poses };
  const after = parseProfile(next);
  if (!after.ok) return { ok: false, errors: after.errors };
  return { ok: true, raw: next, profile: after.profile };
}
