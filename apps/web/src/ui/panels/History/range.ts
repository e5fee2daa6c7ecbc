/**
 * The History panel's time range: a preset (5 min, 1 h, 24 h) ending now, or a custom range
 * from two `datetime-local` inputs (local time). Pure: the clock is an argument. Every view of
 * one load uses the same absolute [start, stop), so charts, tables and CSV agree.
 */

export type RangePreset = '5m' | '1h' | '24h' | 'custom';

export interface TimeRange {
  /** Epoch ms, inclusive. */
  start: number;
  /** Epoch ms, exclusive. */
  stop: number;
}

export const RANGE_PRESETS: readonly {
  id: Exclude<RangePreset, 'custom'>;
  label: string;
  ms: number;
}[] = [
  { id: '5m', label: '5 min', ms: 5 * 60_000 },
  { id: '1h', label: '1 h', ms: 3_600_000 },
  { id: '24h', label: '24 h', ms: 86_400_000 },
];

/** The API's longest range (`maxSpanMs` of the middleware's history options). */
export const MAX_SPAN_MS = 31 * 86_400_000;

export interface RangeChoice {
  preset: RangePreset;
  /** `datetime-local` values (`2024-05-01T10:00`), used when `preset` is `custom`. */
  customStart: string;
  customStop: string;
}

export type RangeResult = { ok: true; range: TimeRange } | { ok: false; error: string };

const LOCAL_INPUT = /^\d{4}-\d{2}-\d{2}T\d{2}:\d{2}(:\d{2}(\.\d{1,3})?)?$/;

/** A `datetime-local` value → epoch ms (local time), or undefined. */
export function parseLocalInput(text: string): number | undefined {
  if (!LOCAL_INPUT.test(text)) return undefined;
  const ms = new Date(text).getTime(); // no offset in the text: ECMAScript reads it as local time
  return Number.isFinite(ms) ? ms : undefined;
}

/** Epoch ms → a `datetime-local` value in local time, to the minute (`exact`: to the ms). */
export function toLocalInput(ms: number, exact = false): string {
  const d = new Date(ms);
  const p = (n: number) => String(n).padStart(2, '0');
  const minute = `${d.getFullYear()}-${p(d.getMonth() + 1)}-${p(d.getDate())}T${p(d.getHours())}:${p(d.getMinutes())}`;
  return exact
    ? `${minute}:${p(d.getSeconds())}.${String(d.getMilliseconds()).padStart(3, '0')}`
    : minute;
}

export function resolveRange(choice: RangeChoice, now: number): RangeResult {
  if (choice.preset !== 'custom') {
    const preset = RANGE_PRESETS.find((p) => p.id === choice.preset)!;
    return { ok: true, range: { start: now - preset.ms, stop: now } };
  }
  const start = parseLocalInput(choice.customStart);
  if (start === undefined) return { ok: false, error: 'Enter a start date and time.' };
  const stop = parseLocalInput(choice.customStop);
  if (stop === undefined) return { ok: false, error: 'Enter an end date and time.' };
  if (start >= stop) return { ok: false, error: 'The start must be before the end.' };
  if (stop - start > MAX_SPAN_MS) return { ok: false, error: 'The range can be at most 31 days.' };
  return { ok: true, range: { start, stop } };
}
