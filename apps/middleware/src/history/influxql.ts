/**
 * InfluxQL builders for the history API and the export, the same questions as the Flux in
 * queries.ts: InfluxQL over the v1 `/query` API is what InfluxDB 1.8, 2.x (through a DBRP
 * mapping, virtual for every bucket) and 3.x all serve. Pure. Identifiers are double-quoted and
 * string literals single-quoted with their quotes and backslashes escaped; times are integers
 * (`…ms`), so [start, stop) is exact on every server.
 *
 * Where InfluxQL cannot say what the Flux says, the rows are still the same:
 * - windows: `GROUP BY time(every)` is epoch-aligned like `aggregateWindow`, but stamps the first
 *   window at its own start rather than at `start`; the reader clips it (`clipToStart`).
 * - alarms: no per-row conditional, so the samples that matter are read in two statements per
 *   field: every sample in an alarm state (a WHERE on the value) and every sample that ends an
 *   episode (the first normal one after an alarm one), found as a step down of a 0/1 alarm
 *   indicator built from `floor` and `ceil` (`difference(…) < 0`). Episode ends carry no value
 *   (only their time matters; see `alarmEndRows`).
 */
import { actualFromMs, THRESHOLDS } from './options.ts';
import type { HistoryParams, IdSet } from './params.ts';

/** `"name"`, with `"` and `\` escaped. */
export const ident = (name: string): string => `"${name.replace(/[\\"]/g, (c) => `\\${c}`)}"`;
/** `'text'`, with `'` and `\` escaped. */
export const literal = (text: string): string => `'${text.replace(/[\\']/g, (c) => `\\${c}`)}'`;

/** ` AND ("id" = '000' OR "id" = '003')`, or nothing for every id. */
export function idCondition(ids: IdSet): string {
  if (ids === 'all') return '';
  return ` AND (${ids.map((id) => `"id" = ${literal(id)}`).join(' OR ')})`;
}

/** `time >= …ms AND time < …ms`: [startMs, stopMs). */
export const timeRange = (startMs: number, stopMs: number): string =>
  `time >= ${Math.floor(startMs)}ms AND time < ${Math.floor(stopMs)}ms`;

/** The WHERE shared by every statement: one measurement's rows of one arm (and ids) in range. */
function where(arm: string, ids: IdSet, startMs: number, stopMs: number): string {
  return `WHERE "arm" = ${literal(arm)}${idCondition(ids)} AND ${timeRange(startMs, stopMs)}`;
}

const fieldOf = (p: HistoryParams): [string, string] =>
  p.field === 'command' ? ['command', 'angle'] : ['servo', p.field];

/** Mean of the field per window, per id (the window's start; the first one clipped by the reader). */
export function seriesStatement(p: HistoryParams, every: string): string {
  const [m, f] = fieldOf(p);
  return `SELECT mean(${ident(f)}) FROM ${ident(m)} ${where(p.arm, p.ids, p.startMs, p.stopMs)} GROUP BY time(${every}), "id" fill(none)`;
}

/** The first `angle` of each servo per window (a pose that really happened). */
export function poseStatement(p: HistoryParams, every: string): string {
  return `SELECT first("angle") FROM "servo" ${where(p.arm, p.ids, p.startMs, p.stopMs)} GROUP BY time(${every}), "id" fill(none)`;
}

/**
 * A 0/1 alarm indicator of each field, from `floor` and `ceil` only (InfluxQL has no
 * conditional): temp ≥ 60 °C → 1 (any temp the protocol allows, 0–999); volt < 6.5 V → 1 (0–65.535 V).
 */
const INDICATOR: Record<'temp' | 'volt', string> = {
  temp: `ceil(floor("temp" / ${THRESHOLDS.tempWarning}) / 1000)`,
  volt: `1 - ceil(floor("volt" / ${THRESHOLDS.undervoltage}) / 1000)`,
};
const ALARM_WHERE: Record<'temp' | 'volt', string> = {
  temp: `"temp" >= ${THRESHOLDS.tempWarning}`,
  volt: `"volt" < ${THRESHOLDS.undervoltage}`,
};

/** The statements of `/history/alarms`, in order: temp alarm samples, temp ends, volt samples, volt ends. */
export function alarmsStatements(p: HistoryParams, maxRows: number): string[] {
  const w = where(p.arm, p.ids, p.startMs, p.stopMs);
  const limit = `LIMIT ${maxRows + 1}`;
  return (['temp', 'volt'] as const).flatMap((f) => [
    `SELECT ${ident(f)} FROM "servo" ${w} AND ${ALARM_WHERE[f]} GROUP BY "id" ${limit}`,
    `SELECT "d" FROM (SELECT difference("a") AS "d" FROM (SELECT ${INDICATOR[f]} AS "a" FROM "servo" ${w} AND ${ident(f)} >= 0 GROUP BY "id") GROUP BY "id") WHERE "d" < 0 AND ${timeRange(p.startMs, p.stopMs)} GROUP BY "id" ${limit}`,
  ]);
}

/**
 * The commands of `/history/tracking`: the last one before `start` (looked for up to
 * `lookbackMs` back), then every one in [start, stop), at most `maxRows + 1`.
 */
export function commandsStatements(
  p: HistoryParams,
  lookbackMs: number,
  maxRows: number,
): string[] {
  return [
    `SELECT last("angle") AS "angle", "ms" FROM "command" ${where(p.arm, p.ids, p.startMs - lookbackMs, p.startMs)} GROUP BY "id"`,
    `SELECT "angle", "ms" FROM "command" ${where(p.arm, p.ids, p.startMs, p.stopMs)} GROUP BY "id" LIMIT ${maxRows + 1}`,
  ];
}

export function actualCountStatement(p: HistoryParams): string {
  return `SELECT count("angle") FROM "servo" ${where(p.arm, p.ids, actualFromMs(p.startMs), p.stopMs)} GROUP BY "id"`;
}

/** Actual `angle` samples per joint: all, or the first of each `every` window (thinned). */
export function actualStatement(p: HistoryParams, every: string | null): string {
  const w = where(p.arm, p.ids, actualFromMs(p.startMs), p.stopMs);
  if (every === null) return `SELECT "angle" FROM "servo" ${w} GROUP BY "id"`;
  return `SELECT first("angle") FROM "servo" ${w} GROUP BY time(${every}), "id" fill(none)`;
}

/** The control events of `/history/audit` (the tag `kind` beside the fields), at most `maxRows + 1`. */
export function auditStatement(p: HistoryParams, maxRows: number): string {
  return `SELECT "by", "detail", "kind" FROM "audit" ${where(p.arm, 'all', p.startMs, p.stopMs)} LIMIT ${maxRows + 1}`;
}

/** Every point of one measurement of one arm in [start, stop), all fields, per id where it has one. */
export function measurementStatement(
  measurement: string,
  arm: string,
  startMs: number,
  stopMs: number,
): string {
  const by = measurement === 'ik' ? '' : ' GROUP BY "id"';
  return `SELECT * FROM ${ident(measurement)} ${where(arm, 'all', startMs, stopMs)}${by}`;
}
