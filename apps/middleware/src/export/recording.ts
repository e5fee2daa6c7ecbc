/**
 * A recording: what InfluxDB holds for one arm over [start, stop), measurement by measurement,
 * one row per stored point (PROTOCOL.md §6), in time order. Times are nanoseconds since the
 * epoch as InfluxDB returns them (the middleware writes µs), so nothing is rounded on the way
 * to MCAP. Pure types and ordering, no I/O.
 */

/** `servo`: a position (`pwm`, `angle`), an angle frame (`angle`) or health (`temp`, `volt`). */
export interface ServoRow {
  ns: bigint;
  id: string;
  pwm?: number;
  angle?: number;
  temp?: number;
  volt?: number;
}

/** `command`: what was asked of a servo. */
export interface CommandRow {
  ns: bigint;
  id: string;
  pwm?: number;
  angle?: number;
  ms?: number;
}

/** `ik`: the outcome of a `$KMS`. */
export interface IkRow {
  ns: bigint;
  code?: number;
  x?: number;
  y?: number;
  z?: number;
  a?: number;
}

/** `audit`: one control event (docs/protocol.md § Control). */
export interface AuditRow {
  ns: bigint;
  kind: string;
  by: string;
  detail: string;
}

export interface Recording {
  arm: string;
  startMs: number;
  stopMs: number;
  servo: ServoRow[];
  command: CommandRow[];
  ik: IkRow[];
  audit: AuditRow[];
}

/** The fields of each measurement, in the order exports write them. */
export const RECORDING_FIELDS = {
  servo: ['pwm', 'angle', 'temp', 'volt'],
  command: ['pwm', 'angle', 'ms'],
  ik: ['code', 'x', 'y', 'z', 'a'],
} as const;

export type Measurement = keyof typeof RECORDING_FIELDS;

/** Sorts rows by time, then servo id (stable for rows of one instant). */
export function byTime<T extends { ns: bigint; id?: string }>(rows: T[]): T[] {
  return rows.sort((a, b) =>
    a.ns < b.ns ? -1 : a.ns > b.ns ? 1 : (a.id ?? '').localeCompare(b.id ?? ''),
  );
}

/**
 * Nanoseconds since the epoch of an RFC 3339 time as InfluxDB writes `_time`
 * (`2026-11-24T06:00:00.123456Z`): exact, unlike `Date.parse`, which keeps milliseconds.
 */
export function nsFromRfc3339(text: string): bigint {
  const m = /^(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d)(?:\.(\d{1,9}))?Z$/.exec(text);
  if (!m) throw new Error(`not an RFC 3339 UTC time: ${JSON.stringify(text)}`);
  const seconds = Date.parse(`${m[1]}Z`);
  if (!Number.isFinite(seconds)) throw new Error(`not a time: ${JSON.stringify(text)}`);
  return BigInt(seconds) * 1_000_000n + BigInt((m[2] ?? '').padEnd(9, '0'));
}
