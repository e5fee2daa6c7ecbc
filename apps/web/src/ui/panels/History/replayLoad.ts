/**
 * Loads the recorded pose of a range (`/history/pose`) into the replay: the replay tab's "Load
 * replay", an episode's "Replay" in the Episodes tab, and a table row's time (`seekReplay`). An
 * empty range closes the replay.
 */
import type { PoseAnswer } from '@armtwin/api';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import type { HistoryApi } from './historyApi.ts';
import type { Loaded } from './loaded.ts';
import type { TimeRange } from './range.ts';

/** The frame count loaded, or the error to show. */
export async function loadReplay(
  api: HistoryApi,
  arm: string,
  range: TimeRange,
  player: ReplayPlayer,
): Promise<Loaded<number>> {
  const r = await api.get<PoseAnswer>('pose', { arm, start: range.start, stop: range.stop });
  if (!r.ok) return r;
  if (r.data.times.length === 0) player.close();
  else player.load({ ...r.data, start: r.data.start, stop: r.data.stop });
  return { ok: true, data: r.data.times.length };
}

/**
 * Moves the replay to t (a table row's time): at once where the replay holds the arm's history
 * around t, else after loading the range's record. The error to show, or null.
 */
export async function seekReplay(
  api: HistoryApi,
  arm: string,
  range: TimeRange,
  player: ReplayPlayer,
  t: number,
): Promise<string | null> {
  const rec = player.record;
  if (!rec || rec.dataset !== undefined || t < rec.start || t > rec.stop) {
    const loaded = await loadReplay(api, arm, range, player);
    if (!loaded.ok) return loaded.error;
    if (loaded.data === 0) return 'No pose recorded in this range: nothing to replay.';
  }
  player.seek(t);
  return null;
}
