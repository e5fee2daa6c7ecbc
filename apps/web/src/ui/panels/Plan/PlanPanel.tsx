/**
 * Plan: waypoints as spheres in the 3D view (add one at the tip or at the Cartesian
 * target, or click the floor with "place" on; drag a sphere to move it, Shift+drag for height;
 * or type the numbers), joint-space or Cartesian path. "Preview" plans from where the arm is
 * (@armtwin/motion, in the page) and the ghost runs along the plan; "Execute" streams it to the
 * arm with pose checking (PlanRunner): paused / re-planned / done / failed are shown. The
 * emergency stop ends it at once. Waypoints taught from history (History → Replay → "Make plan
 * from this range") keep their recorded pose and timing: each is reached in the recorded time,
 * at constant speed (`linear`), and held as long as the arm stood there.
 */
import { useState } from 'react';
import {
  CODE_BELOW_FLOOR,
  motionCodeMessage,
  planRequest,
  planSpec,
  tipPose,
  type MotionMode,
  type MotionRequest,
  type Plan,
  type MotionSpec,
} from '@armtwin/motion';
import '../robots.css';
import { useRobots, usePlan, useArm, useLink, useTarget, useModes } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { MAX_WAYPOINTS } from '../../../core/plan/Waypoints.ts';
import { isTaught, planTargets } from '../../../core/plan/taught.ts';
import { RehearsalSection } from './RehearsalSection.tsx';

/** Speed of HUD plans: a fraction of each servo's limit, and the tip's speed (mm/s). */
const PLAN_SPEED = 0.3;
const PLAN_LINEAR_SPEED = 80;

type Planned = { plan: Plan; spec: MotionSpec };

export function PlanPanel() {
  const robots = useRobots();
  const tools = usePlan();
  const store = useArm();
  const link = useLink();
  const target = useTarget();
  const modes = useModes();
  // The arm a plan runs on: the model copy in Model mode (a rehearsal), else the arm.
  const driven = () => modes.driven(store);
  const { waypoints, preview, runner } = tools;
  const [note, setNote] = useState<{ text: string; bad: boolean } | null>(null);

  const snap = useSampled(() => ({
    version: waypoints.version,
    list: waypoints.list.map((w) => `${w.x},${w.y},${w.z}`),
    placing: waypoints.placing,
    mode: waypoints.mode,
    run: runner.state,
    message: runner.message,
    progress: Math.round(runner.progress * 100),
    enabled:
      link.mayMove &&
      store.connection === 'connected' &&
      !driven().isStale(performance.now()) &&
      robots.active.motion !== null,
    hasTarget: target.active && target.code === 0,
  }));

  const current = (): number[] | null => {
    const pwm = Array.from(driven().pwm);
    return pwm.every(Number.isFinite) ? pwm : null;
  };

  const mode: MotionMode = snap.mode;
  const setMode = (m: MotionMode) => waypoints.setMode(m);

  const plan = (): Planned | null => {
    const motion = robots.active.motion;
    const from = current();
    if (!motion || !from) {
      setNote({ text: 'No plan: the arm has not reported its pose yet.', bad: true });
      return null;
    }
    if (waypoints.list.length === 0) {
      setNote({ text: 'Add a waypoint first.', bad: true });
      return null;
    }
    const request: MotionRequest = {
      id: 'hud-plan',
      mode,
      targets: waypoints.list.map((w) => ({ x: w.x, y: w.y, z: w.z })),
      speed: PLAN_SPEED,
      linearSpeed: PLAN_LINEAR_SPEED,
    };
    const taught = isTaught(waypoints.list);
    const out = taught
      ? planSpec(
          motion,
          {
            mode,
            targets: planTargets(waypoints.list),
            options: { speed: PLAN_SPEED, linearSpeed: PLAN_LINEAR_SPEED, profile: 'linear' },
          },
          from,
        )
      : planRequest(motion, request, from);
    if (out.status !== 'planned') {
      preview.clear();
      const where =
        out.status === 'unreachable'
          ? ` at waypoint ${out.target + 1}${out.step !== undefined ? `, step ${out.step}` : ''}`
          : '';
      // A keep-out refusal (floor 24, zone 25, self-collision 26) names the link and zone.
      const why =
        out.status === 'unreachable' && out.code >= CODE_BELOW_FLOOR
          ? out.message.replace(/^targets\[\d+\]: /, '')
          : motionCodeMessage(out.code);
      setNote({ text: `Unreachable${where}: ${why} (code ${out.code}).`, bad: true });
      return null;
    }
    const p = { plan: out.plan, spec: out.spec };
    preview.show(
      out.plan,
      store.opts.arm.servos.map((s) => s.polarity),
      performance.now(),
    );
    setNote({
      text: `Planned: ${mode === 'joint' ? 'each axis (joint space)' : 'Cartesian path'}${taught && mode === 'joint' ? ' at the recorded pace' : ''}, ${(out.plan.durationMs / 1000).toFixed(1)} s, ${out.plan.samples.length} samples — the ghost previews it.`,
      bad: false,
    });
    return p;
  };

  const execute = () => {
    const motion = robots.active.motion;
    // Always plan again from where the arm is now (it may have moved since the preview).
    const p = plan();
    if (!p || !motion) return;
    const on = driven();
    runner.start(link, on, motion, p.plan, p.spec);
    // A run in Model mode is a rehearsal: the copy's trajectory is kept as the prediction.
    if (modes.mode === 'model')
      tools.recorder.begin('rehearsal', on, performance.now(), waypoints.version);
  };

  /** Rehearse, then run: Twin mode, the same waypoints on the arm, its trajectory recorded. */
  const runOnArm = () => {
    modes.set('twin');
    if (!link.mayMove) {
      setNote({
        text: `Not run: ${link.control.heldBy || 'this page'} cannot move the arm now (control).`,
        bad: true,
      });
      return;
    }
    const motion = robots.active.motion;
    const p = plan();
    if (!p || !motion) return;
    runner.start(link, store, motion, p.plan, p.spec);
    tools.recorder.begin('actual', store, performance.now());
  };

  const addAtTip = () => {
    const motion = robots.active.motion;
    const from = current();
    if (!motion || !from)
      return setNote({ text: 'The arm has not reported its pose yet.', bad: true });
    const tip = tipPose(motion, from);
    waypoints.add({ x: tip.x, y: tip.y, z: tip.z });
    setNote(null);
  };

  const running = snap.run === 'running' || snap.run === 'paused';
  const runText =
    snap.run === 'idle'
      ? ''
      : snap.run === 'running'
        ? `Executing: ${snap.progress}%${runner.replans > 0 ? ` (${snap.message})` : ''}`
        : snap.run === 'paused'
          ? `Paused — ${snap.message.replace(/^paused: /, '')}`
          : snap.message.charAt(0).toUpperCase() + snap.message.slice(1) + '.';

  return (
    <section className="panel plan" aria-labelledby="plan-title">
      <h2 id="plan-title">Plan</h2>
      <div className="plan-mode" role="radiogroup" aria-label="Plan mode">
        <label className="check">
          <input
            type="radio"
            name="plan-mode"
            checked={mode === 'joint'}
            onChange={() => setMode('joint')}
          />
          Each axis
        </label>
        <label className="check">
          <input
            type="radio"
            name="plan-mode"
            checked={mode === 'cartesian'}
            onChange={() => setMode('cartesian')}
          />
          Cartesian path
        </label>
      </div>
      <ol className="waypoints">
        {waypoints.list.map((w, i) => (
          <li key={i} className={w.durationMs !== undefined ? 'waypoint taught' : 'waypoint'}>
            <span className="waypoint-n">{i + 1}</span>
            {(['x', 'y', 'z'] as const).map((k) => (
              <input
                key={k}
                type="number"
                step="any"
                aria-label={`Waypoint ${i + 1} ${k.toUpperCase()}`}
                value={w[k]}
                onChange={(e) => waypoints.move(i, { [k]: Number(e.currentTarget.value) })}
              />
            ))}
            {w.durationMs !== undefined && (
              <span className="waypoint-time dim" title="Taught: time to reach it, then held">
                {(w.durationMs / 1000).toFixed(1)} s
                {w.holdMs ? ` +${(w.holdMs / 1000).toFixed(1)}` : ''}
              </span>
            )}
            <button
              type="button"
              className="small"
              aria-label={`Delete waypoint ${i + 1}`}
              onClick={() => waypoints.remove(i)}
            >
              ×
            </button>
          </li>
        ))}
      </ol>
      <div className="plan-buttons">
        <button type="button" onClick={addAtTip} disabled={waypoints.list.length >= MAX_WAYPOINTS}>
          Add waypoint at tip
        </button>
        <button
          type="button"
          disabled={!snap.hasTarget || waypoints.list.length >= MAX_WAYPOINTS}
          onClick={() => waypoints.add({ x: target.x, y: target.y, z: target.z })}
        >
          Add waypoint at target
        </button>
        <label className="check">
          <input
            type="checkbox"
            checked={snap.placing}
            onChange={(e) => waypoints.setPlacing(e.currentTarget.checked)}
          />
          Click the floor to place waypoints
        </label>
      </div>
      <div className="plan-buttons">
        <button type="button" onClick={() => plan()} disabled={waypoints.list.length === 0}>
          Preview
        </button>
        <button
          type="button"
          onClick={execute}
          disabled={!snap.enabled || running || waypoints.list.length === 0}
        >
          Execute
        </button>
        {running ? (
          <button type="button" onClick={() => runner.cancel('stopped: cancelled')}>
            Cancel plan
          </button>
        ) : (
          <button
            type="button"
            onClick={() => {
              preview.clear();
              waypoints.clear();
              setNote(null);
            }}
            disabled={waypoints.list.length === 0}
          >
            Clear
          </button>
        )}
      </div>
      <p className="dim small-print">
        Each axis: joint-space moves, all axes arriving together. Cartesian path: straight lines
        between waypoints. Drag a sphere to move it, Shift+drag to raise or lower it; mm, z up.
      </p>
      {note && (
        <p className={`note ${note.bad ? 'bad' : 'ok'}`} role="status" data-testid="plan-note">
          {note.text}
        </p>
      )}
      <RehearsalSection onRunOnArm={runOnArm} running={running} />
      {runText && (
        <p
          className={`note ${snap.run === 'failed' || snap.run === 'stopped' ? 'bad' : snap.run === 'paused' ? 'warn' : 'ok'}`}
          role="status"
          data-testid="plan-run"
        >
          {runText}
        </p>
      )}
    </section>
  );
}
