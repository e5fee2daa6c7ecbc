/**
 * Query-string validation for every endpoint. Pure: the clock is an argument. Each failure
 * names the one parameter at fault, so the handler can answer 400 `{error, parameter}`.
 * What passes here is still handed to Flux only through the client's `flux` template.
 */
import { z } from 'zod';
import { HISTORY_FIELDS, type HistoryField } from '@armtwin/api';
import { parseTime } from './time.ts';

export const FIELDS = HISTORY_FIELDS;
export type Field = HistoryField;
/** `export` streams a file (MCAP or CSV, ../export/) instead of answering JSON. */
export type Endpoint =
  'series' | 'alarms' | 'tracking' | 'pose' | 'audit' | 'export' | 'thermal-model';

/** `'all'` or a sorted list of distinct three-digit servo ids. */
export type IdSet = 'all' | string[];

export interface HistoryParams {
  arm: string;
  ids: IdSet;
  /** Only for `series`. */
  field: Field;
  startMs: number;
  stopMs: number;
}

export type ParamsResult =
  { ok: true; params: HistoryParams } | { ok: false; error: string; parameter: string };

export const DEFAULT_START = '-1h';
export const DEFAULT_STOP = 'now';

const ALLOWED: Record<Endpoint, readonly string[]> = {
  series: ['arm', 'id', 'field', 'start', 'stop'],
  alarms: ['arm', 'id', 'start', 'stop'],
  tracking: ['arm', 'id', 'start', 'stop'],
  pose: ['arm', 'id', 'start', 'stop'],
  audit: ['arm', 'start', 'stop', 'format'],
  export: ['arm', 'start', 'stop', 'format', 'profile'],
  'thermal-model': ['arm', 'id', 'start', 'stop'],
};

const armSchema = z.string().regex(/^[a-z0-9-]{1,32}$/);
const fieldSchema = z.enum(FIELDS);
const idSchema = z
  .string()
  .regex(/^\d{3}$/)
  .refine((s) => Number(s) <= 254);

/** Shows a rejected value safely inside an error message (bounded, control chars escaped). */
export function quote(value: string): string {
  const s = JSON.stringify(value.length > 40 ? `${value.slice(0, 40)}…` : value);
  return s;
}

const fail = (parameter: string, error: string): ParamsResult => ({ ok: false, parameter, error });

/** `id=001&id=002`, `id=001,002` or `id=all` (the default). */
export function parseIds(values: string[]): IdSet | { error: string } {
  if (values.length === 0 || (values.length === 1 && values[0] === 'all')) return 'all';
  const ids = new Set<string>();
  for (const part of values.flatMap((v) => v.split(','))) {
    if (!idSchema.safeParse(part).success) {
      return {
        error: `id must be 'all' or three-digit servo ids 000-254, comma-separated; got ${quote(part)}`,
      };
    }
    ids.add(part);
  }
  return [...ids].sort();
}

export function parseParams(
  endpoint: Endpoint,
  query: URLSearchParams,
  nowMs: number,
  maxSpanMs: number,
): ParamsResult {
  const allowed = ALLOWED[endpoint];
  for (const key of new Set(query.keys())) {
    if (!allowed.includes(key))
      return fail(key, `unknown parameter ${quote(key)}; allowed: ${allowed.join(', ')}`);
    if (key !== 'id' && query.getAll(key).length > 1)
      return fail(key, `${key} given more than once`);
  }
  const arm = query.get('arm');
  if (arm === null) return fail('arm', 'arm is required');
  if (!armSchema.safeParse(arm).success)
    return fail('arm', `arm must match [a-z0-9-]{1,32}; got ${quote(arm)}`);

  const ids = parseIds(query.getAll('id'));
  if (ids !== 'all' && !Array.isArray(ids)) return fail('id', ids.error);

  let field: Field = 'angle';
  if (endpoint === 'series') {
    const f = fieldSchema.safeParse(query.get('field'));
    if (!f.success)
      return fail(
        'field',
        `field must be one of ${FIELDS.join(', ')}; got ${quote(query.get('field') ?? '')}`,
      );
    field = f.data;
  }

  const startText = query.get('start') ?? DEFAULT_START;
  const stopText = query.get('stop') ?? DEFAULT_STOP;
  const startMs = parseTime(startText, nowMs);
  if (startMs === undefined)
    return fail('start', `start is not a time (now, -5m, epoch ms, RFC 3339): ${quote(startText)}`);
  const stopMs = parseTime(stopText, nowMs);
  if (stopMs === undefined)
    return fail('stop', `stop is not a time (now, -5m, epoch ms, RFC 3339): ${quote(stopText)}`);
  if (startMs >= stopMs) return fail('start', 'start must be before stop');
  if (stopMs - startMs > maxSpanMs) {
    return fail('start', `the range is longer than the limit of ${maxSpanMs / 86_400_000} days`);
  }
  return { ok: true, params: { arm, ids, field, startMs, stopMs } };
}
