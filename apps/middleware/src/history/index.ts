/** The history API: InfluxQL and Flux readers, pure shaping, and the HTTP handler. */
export { createHistoryHandler, type HistoryHandler, type HistoryHandlerDeps } from './handler.ts';
export { DEFAULT_HISTORY_OPTIONS, THRESHOLDS, type HistoryOptions } from './options.ts';
export { parseParams, FIELDS, type HistoryParams, type Field, type IdSet } from './params.ts';
export { parseTime, parseRfc3339 } from './time.ts';
export { windowFor, windowCount, WINDOW_LADDER } from './window.ts';
export {
  alarmEpisodes,
  detectRuns,
  sortEpisodes,
  type AlarmEpisode,
  type AlarmKind,
} from './alarms.ts';
export { trackingStats, commandedAt, type Command, type TrackingStats } from './tracking.ts';
export * as historyQueries from './queries.ts';
export * as historyStatements from './influxql.ts';
export {
  historyReader,
  QUERY_LANGUAGES,
  type HistoryReader,
  type QueryLanguage,
} from './reader.ts';
export { fluxReader } from './flux-reader.ts';
export { influxqlReader, queryV1 } from './influxql-reader.ts';
