/** The history API: Flux builders, pure shaping, and the HTTP handler. */
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
