/**
 * Reads a recording out of InfluxDB: one Flux query per measurement, fields pivoted into rows
 * (one row per stored point), over [start, stop) of one arm. Flux runs on InfluxDB 1.8 and 2.x;
 * the range ends 1 ns before `stop` for the reason `lastNsBefore` gives. The only I/O is
 * `queryApi.collectRows`.
 */
import { flux, fluxDateTime, type QueryApi } from '@influxdata/influxdb-client';
import { lastNsBefore } from '../history/queries.ts';
import {
  byTime,
  nsFromRfc3339,
  RECORDING_FIELDS,
  type CommandRow,
  type IkRow,
  type Measurement,
  type Recording,
  type ServoRow,
} from './recording.ts';

export interface RecordingSource {
  queryApi: QueryApi;
  /** 2.x bucket, or `db/rp` on 1.8. */
  bucket: string;
}

type Row = Record<string, unknown> & { _time: string; id?: string };

function measurementQuery(
  bucket: string,
  measurement: Measurement,
  arm: string,
  startMs: number,
  stopMs: number,
) {
  return flux`from(bucket: ${bucket})
  |> range(start: ${new Date(startMs)}, stop: ${fluxDateTime(lastNsBefore(stopMs))})
  |> filter(fn: (r) => r._measurement == ${measurement} and r.arm == ${arm})
  |> pivot(rowKey: ["_time"], columnKey: ["_field"], valueColumn: "_value")
  |> drop(columns: ["_start", "_stop", "_measurement", "arm"])`;
}

/** The fields of `m` a row holds, as numbers (absent fields left out). */
function fieldsOf(row: Row, m: Measurement): Record<string, number> {
  const out: Record<string, number> = {};
  for (const f of RECORDING_FIELDS[m]) {
    const v = row[f];
    if (typeof v === 'number' && Number.isFinite(v)) out[f] = v;
  }
  return out;
}

async function rows(src: RecordingSource, m: Measurement, arm: string, a: number, b: number) {
  return src.queryApi.collectRows<Row>(measurementQuery(src.bucket, m, arm, a, b));
}

export async function readRecording(
  src: RecordingSource,
  arm: string,
  startMs: number,
  stopMs: number,
): Promise<Recording> {
  if (!(stopMs > startMs)) throw new RangeError('the end of the range must be after its start');
  const [servo, command, ik] = await Promise.all([
    rows(src, 'servo', arm, startMs, stopMs),
    rows(src, 'command', arm, startMs, stopMs),
    rows(src, 'ik', arm, startMs, stopMs),
  ]);
  const withId = (r: Row) => ({ ns: nsFromRfc3339(r._time), id: String(r.id ?? '') });
  return {
    arm,
    startMs,
    stopMs,
    servo: byTime(servo.map((r): ServoRow => ({ ...withId(r), ...fieldsOf(r, 'servo') }))),
    command: byTime(command.map((r): CommandRow => ({ ...withId(r), ...fieldsOf(r, 'command') }))),
    ik: byTime(ik.map((r): IkRow => ({ ns: nsFromRfc3339(r._time), ...fieldsOf(r, 'ik') }))),
  };
}
