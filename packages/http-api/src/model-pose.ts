/**
 * The body of `POST /api/arms/{id}/model` (docs/protocol.md § Modes): `{"pulses": {"<servo id>":
 * <µs>, …}}` or nothing at all, checked against the arm's servos. Pure.
 */
import { z } from 'zod';

/** Largest body read, bytes: a pose of a few dozen servos is well under 1 KiB. */
export const MAX_MODEL_REQUEST_BYTES = 16 * 1024;

const SERVO_KEY = /^\d{1,3}$/;

const MODEL_REQUEST_SCHEMA = z.strictObject({
  pulses: z.record(z.string(), z.number('a pulse width in µs, a finite number')).optional(),
});

const id3 = (id: number) => String(id).padStart(3, '0');

export type ModelPose = { ok: true; pulses: Map<number, number> } | { ok: false; errors: string[] };

/**
 * The pose a request asks for (servo id → pulse width), or every reason it is refused. `text` is
 * the body ('' or only whitespace: no pose); `servoIds` the arm's servos.
 */
export function parseModelPose(text: string, servoIds: readonly number[]): ModelPose {
  if (text.trim() === '') return { ok: true, pulses: new Map() };
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch {
    return { ok: false, errors: ['the request is not JSON'] };
  }
  const r = MODEL_REQUEST_SCHEMA.safeParse(json);
  const errors = r.success
    ? []
    : r.error.issues.map((i) => {
        const where = i.path.map(String).join('.');
        return where ? `${where}: ${i.message}` : i.message;
      });
  // The keys are checked whatever else is wrong, so that every problem is named at once.
  const raw = (json as { pulses?: unknown } | null)?.pulses;
  const keys = raw && typeof raw === 'object' && !Array.isArray(raw) ? Object.keys(raw) : [];
  const known = new Set(servoIds);
  for (const key of keys) {
    if (!SERVO_KEY.test(key))
      errors.push(`pulses.${key}: a servo id is a number 0–254, e.g. "1" or "001"`);
    else if (!known.has(Number(key)))
      errors.push(
        `pulses.${key}: the arm has no servo ${id3(Number(key))} (it has ${servoIds.map(id3).join(', ')})`,
      );
  }
  if (!r.success || errors.length) return { ok: false, errors };
  const pulses = new Map<number, number>();
  for (const [key, pwm] of Object.entries(r.data.pulses ?? {})) pulses.set(Number(key), pwm);
  return { ok: true, pulses };
}
