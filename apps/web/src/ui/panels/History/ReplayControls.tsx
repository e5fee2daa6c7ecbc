/**
 * Replay of the recorded pose over the selected range: load it (`/history/pose`), then play,
 * pause, pick a speed (0.25×–8×) and scrub (./ReplayScrubber.tsx). The amber sibling arm
 * beside the live one follows; its pose is read by the 3D view's frame loop from the
 * ReplayPlayer, and this panel only
 * samples the position ten times a second. Every camera of the arm plays its recorded video on
 * the same time axis (./ReplayVideo.tsx). A LeRobot dataset's episode plays the same way
 * (./DatasetImport.tsx), its `action` written beside each joint.
 */
import { useState } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import { REPLAY_SPEEDS, type ReplaySpeed } from '../../../core/replay/ReplayClock.ts';
import { fixed } from './format.ts';
import type { HistoryApi } from './historyApi.ts';
import type { TimeRange } from './range.ts';
import { ViewError } from './ViewHeader.tsx';
import { MakePlan } from './MakePlan.tsx';
import { loadReplay } from './replayLoad.ts';
import { DatasetImport } from './DatasetImport.tsx';
import { ReplayVideos, type SegmentSource } from './ReplayVideo.tsx';
import { ReplayScrubber } from './ReplayScrubber.tsx';

const SCRUB_SAMPLE_MS = 100;

export interface ReplayJoint {
  name: string;
  unit: 'deg' | 'mm';
  /** The joint value (deg, or mm for a prismatic axis) of a store angle (degrees). */
  value(storeAngle: number): number;
}

/** `45.0°`, `1500.0 mm`, or `—` while the record has no sample for the servo. */
function jointWords(j: ReplayJoint | undefined, angle: number): string {
  if (Number.isNaN(angle)) return '—';
  if (!j) return `${fixed(angle, 1)}°`;
  return j.unit === 'mm' ? `${fixed(j.value(angle), 1)} mm` : `${fixed(j.value(angle), 1)}°`;
}

export function ReplayControls(props: {
  api: HistoryApi;
  arm: string;
  range: TimeRange | null;
  player: ReplayPlayer;
  /** Per servo of the active robot: its name and the replay's store angle in joint units. */
  joints: readonly ReplayJoint[];
  /** Where the arm's recorded camera segments are read (the middleware's API). */
  segments: SegmentSource;
}) {
  const { player, range } = props;
  const [error, setError] = useState<string | null>(null);
  const [busy, setBusy] = useState(false);
  const [frames, setFrames] = useState<number | null>(null);
  const s = useSampled(
    () => ({
      loaded: player.record !== null,
      dataset: player.record?.dataset !== undefined,
      playing: player.clock.playing,
      speed: player.clock.speed,
      angles: Array.from(player.angles, (a, i) => jointWords(props.joints[i], a)),
      // A dataset's commanded targets at the instant, beside its state.
      actions: player.record?.action
        ? Array.from(player.actionAngles, (a, i) => jointWords(props.joints[i], a))
        : null,
    }),
    SCRUB_SAMPLE_MS,
  );

  const load = () => {
    if (!range) return;
    setBusy(true);
    setError(null);
    loadReplay(props.api, props.arm, range, player)
      .then((r) => {
        setBusy(false);
        if (!r.ok) return setError(r.error);
        setFrames(r.data);
      })
      .catch((err: unknown) => {
        setBusy(false);
        setError(String(err));
      });
  };

  return (
    <div className="history-replay">
      <p className="dim small-print">
        <span className="sibling-swatch" aria-hidden="true" /> The amber arm beside the live one
        replays the record.
      </p>
      <div className="replay-row">
        <button type="button" onClick={load} disabled={!range || busy}>
          {busy ? 'Loading…' : s.loaded ? 'Reload replay' : 'Load replay'}
        </button>
        <button
          type="button"
          disabled={!s.loaded}
          onClick={() => (s.playing ? player.pause() : player.play())}
        >
          {s.playing ? 'Pause' : 'Play'}
        </button>
        <label>
          Speed{' '}
          <select
            aria-label="Replay speed"
            value={String(s.speed)}
            onChange={(e) => player.setSpeed(Number(e.currentTarget.value) as ReplaySpeed)}
          >
            {REPLAY_SPEEDS.map((v) => (
              <option key={v} value={String(v)}>{`${v}×`}</option>
            ))}
          </select>
        </label>
        <button type="button" disabled={!s.loaded} onClick={() => player.close()}>
          Close
        </button>
      </div>
      {error && <ViewError error={error} />}
      {frames === 0 && <p className="dim">No pose recorded in this range.</p>}
      <ReplayScrubber player={player} />
      {s.loaded && (
        <p className="replay-angles" data-testid="replay-angles">
          {props.joints
            .map(
              (j, i) => `${j.name} ${s.angles[i]}${s.actions ? ` (action ${s.actions[i]})` : ''}`,
            )
            .join(' · ')}
        </p>
      )}
      {/* the arm's recorded cameras belong to its history, not to an imported episode */}
      {!s.dataset && <ReplayVideos player={player} arm={props.arm} source={props.segments} />}
      <DatasetImport player={player} />
      <MakePlan player={player} loaded={s.loaded} />
    </div>
  );
}
