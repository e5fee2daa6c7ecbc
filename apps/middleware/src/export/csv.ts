/**
 * A recording as one CSV table, a row per stored point in time order: `time` (RFC 3339 with the
 * stored nanoseconds), `measurement`, `id`, then every field of §6 (empty where the point has
 * none). Pure: rows out as strings.
 */
import { RECORDING_FIELDS, type Recording } from './recording.ts';

const COLUMNS = ['pwm', 'angle', 'temp', 'volt', 'ms', 'code', 'x', 'y', 'z', 'a'] as const;
export const CSV_HEADER = ['time', 'measurement', 'id', ...COLUMNS].join(',');

function rfc3339(ns: bigint): string {
  const ms = ns / 1_000_000n;
  const frac = String(ns % 1_000_000_000n).padStart(9, '0');
  return `${new Date(Number(ms)).toISOString().slice(0, 19)}.${frac}Z`;
}

/** The CSV lines (header first), each ending in `\n`. */
export function* csvLines(rec: Recording): Generator<string> {
  yield `${CSV_HEADER}\n`;
  const rows = [
    ...rec.servo.map((r) => ({ m: 'servo' as const, r })),
    ...rec.command.map((r) => ({ m: 'command' as const, r })),
    ...rec.ik.map((r) => ({ m: 'ik' as const, r })),
  ].sort((a, b) => (a.r.ns < b.r.ns ? -1 : a.r.ns > b.r.ns ? 1 : 0));
  for (const { m, r } of rows) {
    const v = r as unknown as Record<string, number | undefined>;
    const known = new Set<string>(RECORDING_FIELDS[m]);
    const cells = COLUMNS.map((c) => (known.has(c) && v[c] !== undefined ? String(v[c]) : ''));
    yield `${rfc3339(r.ns)},${m},${'id' in r ? r.id : ''},${cells.join(',')}\n`;
  }
}
