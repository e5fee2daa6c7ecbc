/**
 * Reads a recording out of InfluxDB: one query per measurement through the history's reader
 * (InfluxQL or Flux), one row per stored point, over [start, stop) of one arm. The only I/O is
 * the reader's.
 */
import type { HistoryReader } from '../history/reader.ts';
import {
  byTime,
  nsFromRfc3339,
  RECORDING_FIELDS,
  type CommandRow,
  type AuditRow,
  type IkRow,
  type Measurement,
  type Recording,
  type ServoRow,
} from './recording.ts';

type Row = Record<string, unknown> & { _time: string; id?: string };

/** The fields of `m` a row holds, as numbers (absent fields left out). */
function fieldsOf(row: Row, m: Measurement): Record<string, number> {
  const out: Record<string, number> = {};
  for (const f of RECORDING_FIELDS[m]) {
    const v = row[f];
    if (typeof v === 'number' && Number.isFinite(v)) out[f] = v;
  }
  return out;
}

const rows = (reader: HistoryReader, m: Measurement, arm: string, a: number, b: number) =>
  reader.measurement(m, arm, a, b) as Promise<Row[]>;

export async function readRecording(
  src: HistoryReader,
  arm: string,
  startMs: number,
  stopMs: number,
): Promise<Recording> {
  if (!(stopMs > startMs)) throw new RangeError('the end of the range must be after its start');
  const [servo, command, ik, audit] = await Promise.all([
    rows(src, 'servo', arm, startMs, stopMs),
    rows(src, 'command', arm, startMs, stopMs),
    rows(src, 'ik', arm, startMs, stopMs),
    src.measurement('audit', arm, startMs, stopMs) as Promise<Row[]>,
  ]);
  const text = (v: unknown) => (typeof v === 'string' ? v : '');
  const withId = (r: Row) => ({ ns: nsFromRfc3339(r._time), id: String(r.id ?? '') });
  return {
    arm,
    startMs,
    stopMs,
    servo: byTime(servo.map((r): ServoRow => ({ ...withId(r), ...fieldsOf(r, 'servo') }))),
    command: byTime(command.map((r): CommandRow => ({ ...withId(r), ...fieldsOf(r, 'command') }))),
    ik: byTime(ik.map((r): IkRow => ({ ns: nsFromRfc3339(r._time), ...fieldsOf(r, 'ik') }))),
    audit: byTime(
      audit.map((r): AuditRow => ({
        ns: nsFromRfc3339(r._time),
        kind: text(r.kind),
        by: text(r.by),
        detail: text(r.detail),
      })),
    ),
  };
}
