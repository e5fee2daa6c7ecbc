/**
 * Which recorded camera segment shows a replay instant, and when a <video> playing it must be
 * moved (docs/cameras-recording.md: a segment's name holds the epoch ms of its first frame and
 * of its end; its media time 0 is its first frame). Pure: the History replay's video view
 * (ui/panels/History/ReplayVideo.tsx) calls these on each animation frame.
 */

/** A finished segment as `GET …/cameras/{cam}/segments` lists it. */
export interface RecordedSegment {
  name: string;
  startMs: number;
  endMs: number;
}

/** In `list`, sorted by `at`: the index of the last item at or before `t`; -1 if none is. */
export function lastAtOrBefore<T>(list: readonly T[], t: number, at: (item: T) => number): number {
  let lo = 0;
  let hi = list.length - 1;
  let found = -1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (at(list[mid]!) <= t) {
      found = mid;
      lo = mid + 1;
    } else hi = mid - 1;
  }
  return found;
}

/** The segment covering `t` (epoch ms) and the media time of `t` in it (s); null in a gap. */
export function videoAt<S extends RecordedSegment>(
  segments: readonly S[],
  t: number,
): { segment: S; offsetS: number } | null {
  // Sorted by time (the API lists them so): the last one starting at or before t.
  const segment = segments[lastAtOrBefore(segments, t, (s) => s.startMs)];
  if (!segment || t > segment.endMs) return null;
  return { segment, offsetS: (t - segment.startMs) / 1000 };
}

/**
 * How far a playing video may drift from the replay's clock before it is moved, s: browsers
 * play at their own pace, and a seek while playing costs a stall, so small drift is let be.
 */
export const PLAYING_DRIFT_S = 0.25;
/** Paused, the picture must be the replay's instant: anything beyond a millisecond is moved. */
export const PAUSED_DRIFT_S = 0.001;

/** Whether a video at `currentS` must be seeked to `wantS`. */
export function needsSeek(currentS: number, wantS: number, playing: boolean): boolean {
  if (!Number.isFinite(currentS)) return true;
  return Math.abs(currentS - wantS) > (playing ? PLAYING_DRIFT_S : PAUSED_DRIFT_S);
}
