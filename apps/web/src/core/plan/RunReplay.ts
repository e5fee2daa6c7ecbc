/**
 * "Replay run" (rehearse, then run): the actual run on the arm is played by the History panel's
 * replay as the translucent sibling beside the arm, and the ghost plays the rehearsal (the
 * predicted run) at the same time since the start, so predicted and actual move side by side
 * on the replay's clock (play, pause, seek, speed: the History panel's controls). Plain object:
 * the ghost's `sample` runs in the frame loop without allocating.
 */
import type { GhostSource } from '../store/viewSources.ts';
import type { ReplayPlayer, ReplayRecord } from '../replay/ReplayPlayer.ts';
import { traceAt, type RunTrace } from './compareRuns.ts';

/**
 * A run's trace as a replay record (servo ids `000`…, the store's slots) starting at `start`
 * (epoch ms). The record holds each pulse's angle at polarity 1: the store's angle × k. Pure.
 */
export function traceRecord(
  trace: RunTrace,
  polarities: readonly number[],
  start: number,
): ReplayRecord {
  const n = polarities.length;
  return {
    ids: Array.from({ length: n }, (_, k) => String(k).padStart(3, '0')),
    times: trace.t.map((t) => start + t),
    angles: trace.angles.map((row) =>
      Array.from({ length: n }, (_, k) => {
        const a = row[k];
        return a === undefined || !Number.isFinite(a) ? null : a * (polarities[k] === -1 ? -1 : 1);
      }),
    ),
    start,
    stop: start + (trace.t.at(-1) ?? 0),
  };
}

export class RunReplay implements GhostSource {
  private loaded: ReplayRecord | null = null;
  private rehearsal: RunTrace | null = null;

  constructor(private readonly replay: ReplayPlayer) {}

  /** The replay is playing this run (not another record). */
  get playing(): boolean {
    return this.loaded !== null && this.replay.record === this.loaded;
  }

  /** Plays `actual` as the sibling and `rehearsal` as the ghost, from the start. */
  play(actual: RunTrace, rehearsal: RunTrace, polarities: readonly number[]): void {
    this.rehearsal = rehearsal;
    this.loaded = traceRecord(actual, polarities, Date.now());
    this.replay.load(this.loaded);
    this.replay.play();
  }

  close(): void {
    if (this.playing) this.replay.close();
    this.loaded = null;
  }

  sample(_now: number, out: Float64Array): boolean {
    const rec = this.loaded;
    const trace = this.rehearsal;
    if (!rec || !trace || this.replay.record !== rec) return false;
    const t = this.replay.clock.position - rec.start;
    for (let k = 0; k < out.length; k++) out[k] = traceAt(trace, k, t);
    return true;
  }
}
