/**
 * The History panel's Episodes tab (docs/dataset.md): an operator records an episode of the
 * arm's history with a one-line task (Record, then Stop or Discard; the recording time runs
 * while it records), or marks the loaded range as one afterwards; everyone who may read the
 * history sees the list (time range, task, who), and replays an episode on the sibling. A viewer gets no buttons, and is told why.
 * The middleware keeps the marks (`/arms/<arm>/episodes`); `armtwin export --format lerobot`
 * cuts them out as a dataset.
 */
import { useCallback, useEffect, useState } from 'react';
import type { EpisodeMark } from '@armtwin/api';
import { useSession } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { elapsed, type EpisodeRequest, type EpisodesApi } from './episodesApi.ts';
import { clockTime, tableTime } from './format.ts';
import type { Loaded } from './loaded.ts';
import type { TimeRange } from './range.ts';

type Note = { text: string; bad: boolean };

/** How often the open tab re-reads the list. */
const LIST_REFRESH_MS = 5000;

export const MARK_NEEDS_OPERATOR = 'Recording episodes needs an operator account.';

/** A row's button, named for its episode (`Replay episode pick the cube`). */
function RowButton(props: { verb: string; task: string; onClick: () => void }) {
  return (
    <button
      type="button"
      className="small"
      aria-label={`${props.verb} episode ${props.task}`}
      onClick={props.onClick}
    >
      {props.verb}
    </button>
  );
}

function EpisodeRow(props: {
  e: EpisodeMark;
  now: number;
  onReplay: () => void;
  onDiscard: (() => void) | null;
}) {
  const { e, now } = props;
  return (
    <li data-testid="episode">
      <span className="episode-time">
        {tableTime(e.startMs, now)} – {e.stopMs === null ? 'recording' : clockTime(e.stopMs)}
        {e.stopMs !== null && ` (${elapsed(e.stopMs - e.startMs)})`}
      </span>{' '}
      <span className="episode-task">{e.task}</span>{' '}
      <span className="dim">by {e.by || 'unknown'}</span>
      {e.stopMs !== null && <RowButton verb="Replay" task={e.task} onClick={props.onReplay} />}
      {props.onDiscard && e.stopMs !== null && (
        <RowButton verb="Discard" task={e.task} onClick={props.onDiscard} />
      )}
    </li>
  );
}

export function EpisodesView(props: {
  api: EpisodesApi;
  arm: string;
  /** The arm's robot profile (for the export command shown). */
  profile: string;
  range: TimeRange | null;
  /** Shows a stopped episode in the replay. */
  onReplay(range: TimeRange): void;
}) {
  const { api, arm, range } = props;
  const session = useSession();
  const perm = useSampled(() => session.permissions);
  const mayMark = perm?.command === true;
  const [task, setTask] = useState('');
  const [episodes, setEpisodes] = useState<EpisodeMark[] | null>(null);
  const [note, setNote] = useState<Note | null>(null);
  const [busy, setBusy] = useState(false);

  const show = useCallback((r: Loaded<EpisodeMark[]>) => {
    if (r.ok) setEpisodes(r.data);
    else setNote({ text: r.error, bad: true });
  }, []);
  const refresh = async () => show(await api.list(arm));
  // While the tab is open, the list follows marks made elsewhere (another page, the CLI).
  useEffect(() => {
    let live = true;
    const poll = () => void api.list(arm).then((r) => live && show(r));
    poll();
    const id = setInterval(poll, LIST_REFRESH_MS);
    return () => {
      live = false;
      clearInterval(id);
    };
  }, [api, arm, show]);

  const open = episodes?.find((e) => e.stopMs === null && !e.discarded) ?? null;
  /** The clock, to the second: the recording time runs. */
  const now = useSampled(() => Math.floor(Date.now() / 1000) * 1000, 250);

  const act = async (request: EpisodeRequest, done: (e: EpisodeMark) => string) => {
    setBusy(true);
    const r = await api.act(arm, request);
    setBusy(false);
    setNote(r.ok ? { text: done(r.data), bad: false } : { text: r.error, bad: true });
    await refresh();
  };
  const oneLine = task.replace(/\s+/g, ' ').trim();

  return (
    <div className="history-episodes">
      {!mayMark && (
        <p className="dim" data-testid="episodes-reason">
          {MARK_NEEDS_OPERATOR} {perm?.reason ?? ''}
        </p>
      )}
      {mayMark && (
        <div className="replay-row">
          <input
            type="text"
            aria-label="Episode task"
            placeholder="Task, one line: pick up the red cube"
            maxLength={500}
            value={open ? open.task : task}
            disabled={open !== null}
            onChange={(e) => setTask(e.currentTarget.value)}
          />
          {!open && (
            <button
              type="button"
              disabled={busy || !oneLine}
              onClick={() =>
                void act({ action: 'start', task: oneLine }, (e) => `Recording "${e.task}".`)
              }
            >
              Record
            </button>
          )}
          {open && (
            <>
              <span className="episode-recording" role="timer" data-testid="episode-recording">
                ● {elapsed(now - open.startMs)}
              </span>
              <button
                type="button"
                disabled={busy}
                onClick={() =>
                  void act(
                    { action: 'stop' },
                    (e) => `Kept "${e.task}", ${elapsed((e.stopMs ?? e.startMs) - e.startMs)}.`,
                  )
                }
              >
                Stop
              </button>
              <button
                type="button"
                disabled={busy}
                onClick={() => void act({ action: 'discard' }, (e) => `Discarded "${e.task}".`)}
              >
                Discard
              </button>
            </>
          )}
          <button
            type="button"
            disabled={busy || !oneLine || !range || open !== null}
            title="Mark the loaded range of the history as an episode with this task"
            onClick={() =>
              range &&
              void act(
                { action: 'cut', task: oneLine, from: range.start, to: range.stop },
                (e) => `Marked ${clockTime(e.startMs)} – ${clockTime(e.stopMs!)} as "${e.task}".`,
              )
            }
          >
            Mark loaded range
          </button>
        </div>
      )}
      {note && (
        <p className={`note ${note.bad ? 'bad' : 'ok'}`} role="status" data-testid="episodes-note">
          {note.text}
        </p>
      )}
      {episodes && (
        <ul className="episode-list" aria-label="Episodes">
          {episodes
            .filter((e) => !e.discarded)
            .map((e) => (
              <EpisodeRow
                key={e.startMs}
                e={e}
                now={now}
                onReplay={() =>
                  props.onReplay({ start: e.startMs, stop: e.stopMs ?? e.startMs + 1 })
                }
                onDiscard={
                  mayMark
                    ? () =>
                        void act(
                          { action: 'discard', start: e.startMs },
                          (d) => `Discarded "${d.task}".`,
                        )
                    : null
                }
              />
            ))}
        </ul>
      )}
      {episodes?.every((e) => e.discarded) && <p className="dim">No episode yet.</p>}
      <p className="dim small-print">
        Export them as a LeRobot dataset: npx armtwin export --format lerobot --arm {arm} --profile{' '}
        {props.profile} --episodes all --out DIR
      </p>
    </div>
  );
}
