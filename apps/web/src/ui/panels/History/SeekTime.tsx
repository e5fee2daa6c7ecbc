/**
 * A time in a History table that moves the replay there when clicked (the tables and the
 * replay share one time axis). Written as the tables write times; an em dash for none.
 */
import { clockTime, tableTime } from './format.ts';
import type { TableTimeline } from './replayRow.ts';

export function SeekTime({ at, timeline }: { at: number | null; timeline: TableTimeline }) {
  if (at === null) return <>—</>;
  return (
    <button
      type="button"
      className="seek-time"
      title={`Replay from ${clockTime(at)}`}
      onClick={() => timeline.seek(at)}
    >
      {tableTime(at, timeline.ref)}
    </button>
  );
}
