/**
 * The History tables on the replay's time axis: the row at the replay's instant, sampled from
 * the replay player (plain state) ten times a second, as the charts' replay line is. Only the
 * row's index reaches React, and only when it changes.
 */
import { useMemo } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import { rowsByTime } from '../../../core/replay/rowAt.ts';
import type { ReplayAt } from './historyChart.ts';

const REPLAY_SAMPLE_MS = 100;

/** A table's place on the replay's time axis. */
export interface TableTimeline {
  /** The replay's instant on this table's axis (epoch ms; null: no replay on it). */
  replayAt: ReplayAt;
  /** Moves the replay to t (epoch ms): a row's time was clicked. */
  seek(t: number): void;
  /** The instant tables' times are written against (`tableTime`). */
  ref: number;
}

/** The index of the row at the replay's instant (−1: none); `times` in row order, memoised. */
export function useReplayRow(times: readonly (number | null)[], replayAt: ReplayAt | null): number {
  const rowAt = useMemo(() => rowsByTime(times), [times]);
  return useSampled(() => (replayAt ? rowAt(replayAt()) : -1), REPLAY_SAMPLE_MS);
}
