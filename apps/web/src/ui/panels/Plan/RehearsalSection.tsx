/**
 * Rehearse, then run (issue 20; docs/protocol.md § Modes), in the Plan panel: after a plan ran
 * in Model mode on the arm's copy, its trajectory is kept as the rehearsal and `Run on arm`
 * switches to Twin and runs the same waypoints on the real arm (the control claim holds as for
 * any move); once that run ends, predicted vs actual: each servo's largest and mean tracking
 * error against the rehearsal. Samples the recorder (../../../core/plan/RunRecorder.ts); no high-rate state.
 */
import { usePlan, useArm, useModes, useLink } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import './rehearsal.css';

interface Props {
  /** Runs the rehearsed waypoints on the real arm (the panel's Execute, in Twin mode). */
  onRunOnArm(): void;
  running: boolean;
}

const fmt = (v: number) => (Number.isFinite(v) ? v.toFixed(2) : '—');

export function RehearsalSection({ onRunOnArm, running }: Props) {
  const plan = usePlan();
  const store = useArm();
  const modes = useModes();
  const link = useLink();
  const rec = plan.recorder;
  const snap = useSampled(() => ({
    phase: rec.phase,
    version: rec.version,
    stale: rec.waypointsVersion !== plan.waypoints.version,
    samples: rec.rehearsal?.t.length ?? 0,
    seconds: ((rec.rehearsal?.t.at(-1) ?? 0) / 1000).toFixed(1),
    mayCommand: link.permissions.command,
    mode: modes.mode,
    replaying: plan.runReplay.playing,
  }));
  const replayRun = () => {
    if (plan.runReplay.playing) return plan.runReplay.close();
    if (rec.actual && rec.rehearsal)
      plan.runReplay.play(
        rec.actual,
        rec.rehearsal,
        store.opts.arm.servos.map((s) => s.polarity),
      );
  };
  if (snap.phase === 'none') return null;
  const names = store.opts.arm.servos.map((s) => s.name);
  return (
    <div className="rehearsal" data-testid="rehearsal">
      {snap.phase === 'rehearsing' && (
        <p className="note ok" role="status">
          Rehearsing on the model copy: its trajectory is kept as the prediction.
        </p>
      )}
      {(snap.phase === 'rehearsed' || snap.phase === 'compared' || snap.phase === 'running') && (
        <p className="dim small-print">
          Rehearsal kept: {snap.seconds} s, {snap.samples} reports from the copy.
          {snap.stale ? ' The waypoints changed since: rehearse again to run them on the arm.' : ''}
        </p>
      )}
      {(snap.phase === 'rehearsed' || snap.phase === 'compared') && (
        <button
          type="button"
          onClick={onRunOnArm}
          disabled={running || snap.stale || !snap.mayCommand}
          title="Switch to Twin and run the rehearsed plan on the real arm"
        >
          Run on arm
        </button>
      )}
      {snap.phase === 'running' && (
        <p className="note ok" role="status">
          Running the rehearsed plan on the arm: recording the actual trajectory.
        </p>
      )}
      {snap.phase === 'compared' && (
        <button
          type="button"
          onClick={replayRun}
          aria-pressed={snap.replaying}
          title="The actual run as the amber sibling, the rehearsal as the ghost, side by side (History panel's replay controls)"
        >
          Replay run
        </button>
      )}
      {snap.phase === 'compared' && rec.errors && (
        <table className="tracking-table" data-testid="predicted-vs-actual">
          <caption>Predicted vs actual: tracking error (°)</caption>
          <thead>
            <tr>
              <th scope="col">Servo</th>
              <th scope="col">max</th>
              <th scope="col">mean</th>
            </tr>
          </thead>
          <tbody>
            {rec.errors.map((e) => (
              <tr key={e.index}>
                <th scope="row">{names[e.index] ?? `servo ${e.index}`}</th>
                <td>{fmt(e.maxDeg)}</td>
                <td>{fmt(e.meanDeg)}</td>
              </tr>
            ))}
          </tbody>
        </table>
      )}
    </div>
  );
}
