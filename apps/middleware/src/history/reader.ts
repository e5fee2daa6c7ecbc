/**
 * What the history API and the export ask of InfluxDB, as one interface with two languages
 * behind it: Flux (InfluxDB 1.8 with `flux-enabled`, 2.x) and InfluxQL over the v1 `/query`
 * API (1.8, 2.x, 3.x). Each method answers rows in the same shape whichever language ran, so
 * the endpoints' figures are identical (tests/integration/history-api.test.ts runs both on
 * every server it can start).
 */
import { fluxReaderFor } from './flux-reader.ts';
import { influxqlReader } from './influxql-reader.ts';
import type { HistoryParams } from './params.ts';
import type { Row } from './shape.ts';

export const QUERY_LANGUAGES = ['influxql', 'flux'] as const;
export type QueryLanguage = (typeof QUERY_LANGUAGES)[number];

export interface HistoryReader {
  readonly language: QueryLanguage;
  /** Mean of `p.field` per `every` window per id: `_time` (window start, ≥ start), `_value`, `id`. */
  series(p: HistoryParams, every: string): Promise<Row[]>;
  /** First `angle` per window per id: `_time`, `_value`, `id`. */
  pose(p: HistoryParams, every: string): Promise<Row[]>;
  /**
   * The temp and volt samples that matter for episodes (every one in an alarm state, every one
   * ending an episode), ≤ maxRows + 1 per (field, id): `_time`, `_value`, `_field`, `id`. An
   * episode's end may carry `_value: NaN` (InfluxQL): it is known to be normal, nothing more.
   */
  alarms(p: HistoryParams, maxRows: number): Promise<Row[]>;
  /** The command in force at start (looked for `lookbackMs` back) and those in range: `_time`, `id`, `angle`, `ms`. */
  commands(p: HistoryParams, lookbackMs: number, maxRows: number): Promise<Row[]>;
  /** Actual `angle` samples per id in the tracking window: `_value` (count), `id`. */
  actualCount(p: HistoryParams): Promise<Row[]>;
  /** Actual `angle` samples: all (`every` null) or the first per window, stamped at its start. */
  actual(p: HistoryParams, every: string | null): Promise<Row[]>;
  /** The arm's control events in range, ≤ maxRows + 1: `_time`, `kind`, `by`, `detail`. */
  audit(p: HistoryParams, maxRows: number): Promise<Row[]>;
  /** Every point of a measurement of an arm in [start, stop), one row per point: `_time`, `id`, fields. */
  measurement(measurement: string, arm: string, startMs: number, stopMs: number): Promise<Row[]>;
}

/** Where a reader reads: the middleware's own INFLUX_* settings. */
export interface InfluxSource {
  url: string;
  /** 2.x/3.x token, or `user:password` on 1.8 (empty = none). */
  token: string;
  /** 2.x org (Flux only). */
  org: string;
  /** 2.x bucket, `db/rp` on 1.8, the database on 3.x. */
  bucket: string;
  /** Request timeout, ms. */
  timeoutMs: number;
}

/** The reader for a source in a language. */
export function historyReader(src: InfluxSource, language: QueryLanguage): HistoryReader {
  return language === 'flux' ? fluxReaderFor(src) : influxqlReader(src);
}
