/**
 * The answers of the middleware's history API (apps/middleware/src/history/README.md), as
 * the HUD reads them. Times are epoch ms. Every answer carries `arm`, `start`, `stop`.
 */

export interface RangeEcho {
  arm: string;
  start: number;
  stop: number;
}

export type SeriesField = 'temp' | 'volt' | 'angle' | 'command';

export interface SeriesAnswer extends RangeEcho {
  field: SeriesField;
  every: string;
  everyMs: number;
  series: { id: string; times: number[]; values: number[] }[];
}

export interface PoseAnswer extends RangeEcho {
  every: string;
  everyMs: number;
  /** Servo ids, the order of each frame's angles. */
  ids: string[];
  /** Frame times, ascending. */
  times: number[];
  /** angles[frame][i] belongs to ids[i]; null before that servo's first sample. */
  angles: (number | null)[][];
}

export type AlarmKind = 'temp-warning' | 'temp-critical' | 'undervoltage';

export interface AlarmEpisode {
  kind: AlarmKind;
  arm: string;
  id: string;
  start: number;
  /** null: still in the alarm state at the end of the range. */
  end: number | null;
  /** Highest temperature (°C) or lowest voltage (V). */
  peak: number;
}

export interface AlarmsAnswer extends RangeEcho {
  truncated: boolean;
  episodes: AlarmEpisode[];
}

export interface TrackingJoint {
  id: string;
  samples: number;
  meanAbsError: number | null;
  maxAbsError: number | null;
  maxAt: number | null;
}

export interface TrackingAnswer extends RangeEcho {
  unit: 'deg';
  stride: number;
  truncated: boolean;
  joints: TrackingJoint[];
}

/** A loaded view, or the text to show instead of it. */
export type Loaded<T> = { ok: true; data: T } | { ok: false; error: string };
