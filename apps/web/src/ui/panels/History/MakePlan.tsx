/**
 * Teaching by showing, in the replay's controls: "Make plan from this range" turns the recorded
 * pose of the loaded range (or of the stretch between two marks set with the scrubber) into
 * waypoints where the motion changes (`teachFromRecording`, @armtwin/motion), and puts them in
 * the Plan panel, where they can be edited, previewed on the ghost and executed.
 */
import { useState } from 'react';
import { DEFAULT_TEACH_OPTIONS, teachFromRecording } from '@armtwin/motion';
import { useRobots, usePlan } from '../../hud/HudParts.ts';
import type { ReplayPlayer } from '../../../core/replay/ReplayPlayer.ts';
import { recordingFromPose, waypointsFromTaught } from '../../../core/plan/taught.ts';
import { clockTime, fixed } from './format.ts';
import { historyProbe } from './probe.ts';

type Note = { text: string; bad: boolean };

export function MakePlan(props: { player: ReplayPlayer; loaded: boolean }) {
  const robots = useRobots();
  const plan = usePlan();
  const { player, loaded } = props;
  const [from, setFrom] = useState<number | null>(null);
  const [to, setTo] = useState<number | null>(null);
  const [note, setNote] = useState<Note | null>(null);

  const make = () => {
    const motion = robots.active.motion;
    const rec = player.record;
    if (!rec) return setNote({ text: 'Load the replay first.', bad: true });
    if (!motion) return setNote({ text: 'No planner for this arm yet (its profile).', bad: true });
    const lo = from ?? -Infinity;
    const hi = to ?? Infinity;
    const keep = rec.times.flatMap((t, k) => (t >= lo && t <= hi ? [k] : []));
    const recording = recordingFromPose(motion, {
      ids: rec.ids,
      times: keep.map((k) => rec.times[k]!),
      angles: keep.map((k) => rec.angles[k]!),
    });
    const r = teachFromRecording(motion, recording);
    if (!r.ok) {
      historyProbe.teach = null;
      return setNote({ text: `No plan: ${r.error}.`, bad: true });
    }
    plan.preview.clear();
    plan.waypoints.setTaught(waypointsFromTaught(motion, r.waypoints));
    historyProbe.teach = { samples: r.samples, waypoints: r.waypoints.length, error: r.error };
    const o = DEFAULT_TEACH_OPTIONS;
    setNote({
      text: `Plan made: ${r.waypoints.length} waypoints from ${r.samples} samples, within ${fixed(r.error.maxDeg, 1)}° and ${fixed(r.error.maxTipMm, 1)} mm of the recording (tolerance ${o.jointDeg}°, ${o.tipMm} mm). Edit, preview or execute it in the Plan panel.`,
      bad: false,
    });
  };

  return (
    <div className="history-teach">
      <div className="replay-row">
        <button type="button" disabled={!loaded} onClick={make}>
          Make plan from this range
        </button>
        <button
          type="button"
          disabled={!loaded}
          onClick={() => setFrom(player.clock.position)}
          title="Start the plan's stretch at the replay's position"
        >
          From here
        </button>
        <button
          type="button"
          disabled={!loaded}
          onClick={() => setTo(player.clock.position)}
          title="End the plan's stretch at the replay's position"
        >
          To here
        </button>
        {(from !== null || to !== null) && (
          <button
            type="button"
            onClick={() => {
              setFrom(null);
              setTo(null);
            }}
          >
            Whole range
          </button>
        )}
      </div>
      <p className="dim small-print" data-testid="teach-stretch">
        {from === null && to === null
          ? 'Stretch: the whole loaded range.'
          : `Stretch: ${from === null ? 'start' : clockTime(from)} – ${to === null ? 'end' : clockTime(to)}.`}
      </p>
      {note && (
        <p className={`note ${note.bad ? 'bad' : 'ok'}`} role="status" data-testid="teach-note">
          {note.text}
        </p>
      )}
    </div>
  );
}
