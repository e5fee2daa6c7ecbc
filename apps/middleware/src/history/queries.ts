/**
 * Flux query builders. Pure: each returns a `ParameterizedQuery` from the client's `flux`
 * tagged template, so every value (bucket, arm, ids, field, numbers) is rendered as an
 * escaped Flux literal; times are `Date`s we built ourselves and durations go through
 * `fluxDuration`. Flux only, nothing version-specific: runs on InfluxDB 1.8 (Flux 0.6x) and 2.x.
 */
import {
  flux,
  fluxDateTime,
  fluxDuration,
  fluxExpression,
  fluxFloat,
  fluxInteger,
  toFluxValue,
  type ParameterizedQuery,
} from '@influxdata/influxdb-client';
import { actualFromMs, THRESHOLDS } from './options.ts';
import type { Field, HistoryParams, IdSet } from './params.ts';

/** ` and (r.id == "000" or r.id == "003")`, or nothing for every id. Ids are escaped again here. */
export function idClause(ids: IdSet): ParameterizedQuery {
  if (ids === 'all') return flux``;
  return flux` and (${fluxExpression(ids.map((id) => `r.id == ${toFluxValue(id)}`).join(' or '))})`;
}

/**
 * The last nanosecond before `stopMs`, as RFC 3339. `range()` should exclude its stop, but
 * InfluxDB 1.8 includes it (influxdata/influxdb#19966) and then files that point in a stray
 * window; stopping 1 ns earlier gives [start, stop) on 1.8 and on 2.x alike, and keeps 2.x's
 * storage push-downs (a `filter` on `_time` would not).
 */
export function lastNsBefore(stopMs: number): string {
  return `${new Date(stopMs - 1).toISOString().slice(0, -1)}999999Z`;
}

/** The `from |> range |> filter` head shared by every query: [startMs, stopMs). */
function head(
  bucket: string,
  measurement: string,
  arm: string,
  fields: readonly string[],
  ids: IdSet,
  startMs: number,
  stopMs: number,
): ParameterizedQuery {
  const fieldExpr = fluxExpression(fields.map((f) => `r._field == ${toFluxValue(f)}`).join(' or '));
  const q = flux`from(bucket: ${bucket})
  |> range(start: ${new Date(startMs)}, stop: ${fluxDateTime(lastNsBefore(stopMs))})
  |> filter(fn: (r) => r._measurement == ${measurement} and r.arm == ${arm} and (${fieldExpr})${idClause(ids)})`;
  // A command's author is a tag (`user`, docs/protocol.md § Control), so one servo's commands
  // may be several series: one table per servo and field, in time order, as InfluxQL's GROUP BY "id".
  if (measurement !== 'command') return q;
  return flux`${q}
  |> group(columns: ["id", "_field"])
  |> sort(columns: ["_time"])`;
}

/**
 * Mean of `field` per window, one table per servo id: `_time` (window start), `_value`, `id`.
 * `command` reads the commanded `angle` (measurement `command`) instead of the servo's.
 */
export function seriesQuery(bucket: string, p: HistoryParams, every: string): ParameterizedQuery {
  const [measurement, field] = p.field === 'command' ? ['command', 'angle'] : ['servo', p.field];
  return flux`${head(bucket, measurement, p.arm, [field], p.ids, p.startMs, p.stopMs)}
  |> aggregateWindow(every: ${fluxDuration(every)}, fn: mean, createEmpty: false, timeSrc: "_start")
  |> keep(columns: ["_time", "_value", "id"])`;
}

/** The first `angle` of each servo per window, stamped at the window start (a pose that really happened), for replay. */
export function poseQuery(bucket: string, p: HistoryParams, every: string): ParameterizedQuery {
  return flux`${head(bucket, 'servo', p.arm, ['angle'], p.ids, p.startMs, p.stopMs)}
  |> aggregateWindow(every: ${fluxDuration(every)}, fn: first, createEmpty: false, timeSrc: "_start")
  |> keep(columns: ["_time", "_value", "id"])`;
}

/**
 * Raw `temp` and `volt` samples reduced in Flux to those that matter for episodes: every
 * sample in an alarm state, and every sample whose alarm level differs from the previous
 * one (so each episode's first normal sample, its end, is kept). Level: temp 0/1/2 (≥ 60,
 * ≥ 75), volt 0/1 (< 6.5). At most `maxRows + 1` rows per series (`+1` reveals truncation).
 */
export function alarmsQuery(bucket: string, p: HistoryParams, maxRows: number): ParameterizedQuery {
  const warn = fluxFloat(THRESHOLDS.tempWarning);
  const crit = fluxFloat(THRESHOLDS.tempCritical);
  const low = fluxFloat(THRESHOLDS.undervoltage);
  return flux`temp = ${head(bucket, 'servo', p.arm, ['temp'], p.ids, p.startMs, p.stopMs)}
  |> map(fn: (r) => ({r with level: if r._value >= ${crit} then 2 else if r._value >= ${warn} then 1 else 0}))
volt = ${head(bucket, 'servo', p.arm, ['volt'], p.ids, p.startMs, p.stopMs)}
  |> map(fn: (r) => ({r with level: if r._value < ${low} then 1 else 0}))
union(tables: [temp, volt])
  |> map(fn: (r) => ({r with change: r.level}))
  |> difference(columns: ["change"], keepFirst: true)
  |> filter(fn: (r) => r.level > 0 or not exists r.change or r.change != 0)
  |> limit(n: ${fluxInteger(maxRows + 1)})
  |> keep(columns: ["_time", "_value", "_field", "id"])`;
}

/**
 * Commands (`angle`, `ms`) per joint: the last one before `start` (it may still be in force,
 * looked for up to `lookbackMs` back) and every one in [start, stop), at most `maxRows + 1`.
 */
export function commandsQuery(
  bucket: string,
  p: HistoryParams,
  lookbackMs: number,
  maxRows: number,
): ParameterizedQuery {
  const fields = ['angle', 'ms'];
  return flux`before = ${head(bucket, 'command', p.arm, fields, p.ids, p.startMs - lookbackMs, p.startMs)}
  |> last()
during = ${head(bucket, 'command', p.arm, fields, p.ids, p.startMs, p.stopMs)}
  |> limit(n: ${fluxInteger(maxRows + 1)})
union(tables: [before, during])
  |> pivot(rowKey: ["_time"], columnKey: ["_field"], valueColumn: "_value")
  |> keep(columns: ["_time", "id", "angle", "ms"])`;
}

/** How many actual `angle` samples each joint has in the tracking window. */
export function actualCountQuery(bucket: string, p: HistoryParams): ParameterizedQuery {
  return flux`${head(bucket, 'servo', p.arm, ['angle'], p.ids, actualFromMs(p.startMs), p.stopMs)}
  |> count()
  |> keep(columns: ["_value", "id"])`;
}

/** Actual `angle` samples per joint: all, or the first of each `every` window (thinned). */
export function actualQuery(
  bucket: string,
  p: HistoryParams,
  every: string | null,
): ParameterizedQuery {
  const q = head(bucket, 'servo', p.arm, ['angle'], p.ids, actualFromMs(p.startMs), p.stopMs);
  if (every === null)
    return flux`${q}
  |> keep(columns: ["_time", "_value", "id"])`;
  return flux`${q}
  |> aggregateWindow(every: ${fluxDuration(every)}, fn: first, createEmpty: false, timeSrc: "_start")
  |> keep(columns: ["_time", "_value", "id"])`;
}

/** The control events of `/history/audit`, one row per event in time order, at most `maxRows + 1`. */
export function auditQuery(bucket: string, p: HistoryParams, maxRows: number): ParameterizedQuery {
  return flux`from(bucket: ${bucket})
  |> range(start: ${new Date(p.startMs)}, stop: ${fluxDateTime(lastNsBefore(p.stopMs))})
  |> filter(fn: (r) => r._measurement == "audit" and r.arm == ${p.arm})
  |> pivot(rowKey: ["_time"], columnKey: ["_field"], valueColumn: "_value")
  |> group()
  |> sort(columns: ["_time"])
  |> limit(n: ${fluxInteger(maxRows + 1)})
  |> keep(columns: ["_time", "kind", "by", "detail"])`;
}

/** Every point of one measurement of one arm in [start, stop), fields pivoted into one row per point. */
export function measurementQuery(
  bucket: string,
  measurement: string,
  arm: string,
  startMs: number,
  stopMs: number,
): ParameterizedQuery {
  return flux`from(bucket: ${bucket})
  |> range(start: ${new Date(startMs)}, stop: ${fluxDateTime(lastNsBefore(stopMs))})
  |> filter(fn: (r) => r._measurement == ${measurement} and r.arm == ${arm})
  |> pivot(rowKey: ["_time"], columnKey: ["_field"], valueColumn: "_value")
  |> drop(columns: ["_start", "_stop", "_measurement", "arm"])`;
}

export type { Field };
