/**
 * The replay's scrubber: its position as a slider over the record's range, with the start, the
 * instant and the stop written under it. The replay tab holds it under its controls; the tables
 * tab repeats it with a Play button (`ReplayStrip`), so the tables' marked rows can be followed
 * while scrubbing. Reads the player (plain state) ten times a second.
 */
import { useSampled } from '../../hud/useSampled.ts';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import { clockTime } from './format.ts';

const SCRUB_SAMPLE_MS = 100;

export function ReplayScrubber({ player }: { player: ReplayPlayer }) {
  const s = useSampled(
    () => ({
      loaded: player.record !== null,
      position: player.clock.position,
      start: player.clock.start,
      stop: player.clock.stop,
    }),
    SCRUB_SAMPLE_MS,
  );
  return (
    <>
      <input
        type="range"
        className="replay-scrubber"
        aria-label="Replay position"
        aria-valuetext={s.loaded ? clockTime(s.position) : 'no record loaded'}
        min={s.start}
        max={s.stop}
        step={1}
        value={s.position}
        disabled={!s.loaded}
        onChange={(e) => player.seek(Number(e.currentTarget.value))}
      />
      <div className="replay-times dim">
        <span>{s.loaded ? clockTime(s.start) : '—'}</span>
        <span data-testid="replay-position">{s.loaded ? clockTime(s.position) : '—'}</span>
        <span>{s.loaded ? clockTime(s.stop) : '—'}</span>
      </div>
    </>
  );
}

/** Play/Pause and the scrubber, above the tables; a hint while no replay of the history is loaded. */
export function ReplayStrip({ player }: { player: ReplayPlayer }) {
  const s = useSampled(
    () => ({
      onHistory: player.record !== null && player.record.dataset === undefined,
      playing: player.clock.playing,
    }),
    SCRUB_SAMPLE_MS,
  );
  if (!s.onHistory)
    return (
      <p className="dim small-print" data-testid="tables-replay-hint">
        Click a time to replay the range from there.
      </p>
    );
  return (
    <div className="history-replay tables-replay">
      <button type="button" onClick={() => (s.playing ? player.pause() : player.play())}>
        {s.playing ? 'Pause' : 'Play'}
      </button>
      <ReplayScrubber player={player} />
    </div>
  );
}
