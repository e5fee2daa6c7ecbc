/**
 * Alarm episodes from raw samples. Pure. An episode is a maximal run of consecutive samples
 * of one servo that meet a condition (PROTOCOL.md §5):
 *
 *   temp-warning   temp ≥ 60 °C   (includes the time spent ≥ 75 °C: episodes nest)
 *   temp-critical  temp ≥ 75 °C
 *   undervoltage   volt < 6.5 V
 *
 * `start` is the first sample meeting the condition, `end` the first sample after it that
 * no longer does (the alarm cleared), `null` when the last sample still meets it. `peak` is
 * the worst value in the run: the highest temperature, the lowest voltage.
 */
import type { AlarmEpisode, AlarmKind } from '@armtwin/api';
import { THRESHOLDS } from './options.ts';

export type { AlarmEpisode, AlarmKind };

export interface Sample {
  /** Epoch ms. */
  t: number;
  v: number;
}

interface Rule {
  kind: AlarmKind;
  field: 'temp' | 'volt';
  active(v: number): boolean;
  /** true when a is worse than b. */
  worse(a: number, b: number): boolean;
}

export const ALARM_RULES: readonly Rule[] = [
  {
    kind: 'temp-warning',
    field: 'temp',
    active: (v) => v >= THRESHOLDS.tempWarning,
    worse: (a, b) => a > b,
  },
  {
    kind: 'temp-critical',
    field: 'temp',
    active: (v) => v >= THRESHOLDS.tempCritical,
    worse: (a, b) => a > b,
  },
  {
    kind: 'undervoltage',
    field: 'volt',
    active: (v) => v < THRESHOLDS.undervoltage,
    worse: (a, b) => a < b,
  },
];

/** Runs of `samples` (sorted by time) where `active` holds. */
export function detectRuns(
  samples: readonly Sample[],
  active: (v: number) => boolean,
  worse: (a: number, b: number) => boolean,
): { start: number; end: number | null; peak: number }[] {
  const runs: { start: number; end: number | null; peak: number }[] = [];
  let open: { start: number; end: number | null; peak: number } | undefined;
  for (const s of samples) {
    if (active(s.v)) {
      if (!open) {
        open = { start: s.t, end: null, peak: s.v };
        runs.push(open);
      } else if (worse(s.v, open.peak)) open.peak = s.v;
    } else if (open) {
      open.end = s.t;
      open = undefined;
    }
  }
  return runs;
}

/** Every episode of one servo's `field` samples (sorted by time). */
export function alarmEpisodes(
  arm: string,
  id: string,
  field: 'temp' | 'volt',
  samples: readonly Sample[],
): AlarmEpisode[] {
  const out: AlarmEpisode[] = [];
  for (const rule of ALARM_RULES) {
    if (rule.field !== field) continue;
    for (const run of detectRuns(samples, rule.active, rule.worse))
      out.push({ kind: rule.kind, arm, id, ...run });
  }
  return out;
}

const KIND_ORDER: Record<AlarmKind, number> = {
  'temp-warning': 0,
  'temp-critical': 1,
  undervoltage: 2,
};

/** Log order: by start, then servo id, then kind. */
export function sortEpisodes(episodes: AlarmEpisode[]): AlarmEpisode[] {
  return episodes.sort(
    (a, b) =>
      a.start - b.start || a.id.localeCompare(b.id) || KIND_ORDER[a.kind] - KIND_ORDER[b.kind],
  );
}
