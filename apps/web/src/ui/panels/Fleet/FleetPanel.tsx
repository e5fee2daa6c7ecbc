/**
 * Fleet: every arm on the broker at a glance (docs/protocol.md § Fleets): its robot, whether it
 * is online, its state (moving, still, not ready), who holds it, a health badge (PROTOCOL.md §5
 * levels) with the thermal model's early warnings, and a small live pose, all from the arms'
 * retained summaries, so the page's work does not grow with the fleet. The shown arm's health
 * comes from its full stream in the store. Selecting one makes the HUD control it (the URL's
 * `arm=` follows). The list folds away. Arm ids and titles are text only. Who controls the
 * selected arm is said under the heading (./ControlBar.tsx).
 */
import '../robots.css';
import { healthSummary } from '@armtwin/protocol';
import { useRobots, useSettings, useArm, useReconnect } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { fleetList, type FleetArm } from '../../../core/robots/fleet.ts';
import { ControlBar } from './ControlBar.tsx';
import { PoseBars } from './PoseBars.tsx';
import { isModelArmId, MODEL_ARM_SUFFIX } from '../../../core/link/modes.ts';

const onlineWord = (o: boolean | null) =>
  o === true ? 'online' : o === false ? 'offline' : 'unknown';
const LEVEL_WORDS = {
  normal: 'ok',
  warning: 'warning',
  critical: 'alarm',
  unknown: 'no health yet',
} as const;
const stateWords = (a: FleetArm): string =>
  a.state === null ? '' : a.state === 'not-ready' ? `not ready: ${a.why}` : a.state;

export function FleetPanel() {
  const robots = useRobots();
  const settings = useSettings();
  const store = useArm();
  const { selectArm } = useReconnect();
  const selected = settings.armId;
  const snap = useSampled(() => {
    const fleet = robots.fleet;
    const rows = fleetList(fleet.state).map((a): FleetArm => {
      if (a.id !== selected) return a;
      // The selected arm's health is in the store, at full rate.
      const health: Record<number, { temp: number; mv: number }> = {};
      store.opts.arm.servos.forEach((s, i) => {
        health[s.id] = { temp: store.temp[i]!, mv: store.mv[i]! };
      });
      const h = healthSummary(health);
      return { ...a, level: h.level, alarm: h.alarm };
    });
    return {
      version: fleet.version,
      rows: rows.map((r) => ({
        id: r.id,
        online: r.online,
        // A model copy (docs/protocol.md § Modes) is said to be one.
        robot: `${isModelArmId(r.id) ? `model copy of ${r.id.slice(0, -MODEL_ARM_SUFFIX.length)} · ` : ''}${r.title ?? r.profileName ?? 'no profile announced'}`,
        level: r.level,
        alarm: r.alarm,
        state: stateWords(r),
        holder: r.holder,
        joints: r.joints,
        warning: Object.values(r.warnings).join('; '),
        error: r.error?.text ?? '',
      })),
    };
  });
  const online = snap.rows.filter((r) => r.online === true).length;
  const alarms = snap.rows.filter((r) => r.level === 'critical' || r.level === 'warning').length;
  return (
    <section className="panel fleet" aria-labelledby="fleet-title">
      <h2 id="fleet-title">Fleet</h2>
      <ControlBar />
      {snap.rows.length === 0 ? (
        <p className="dim">No arms seen on the broker yet.</p>
      ) : (
        <details className="fleet-view" open>
          <summary data-testid="fleet-count">
            {snap.rows.length} arm{snap.rows.length === 1 ? '' : 's'} · {online} online
            {alarms > 0 ? ` · ${alarms} with an alarm or warning` : ''}
          </summary>
          <ul className="fleet-list">
            {snap.rows.map((r) => (
              <li key={r.id}>
                <button
                  type="button"
                  className={`fleet-arm${r.id === selected ? ' selected' : ''}`}
                  aria-pressed={r.id === selected}
                  data-testid={`fleet-${r.id}`}
                  onClick={() => selectArm(r.id)}
                >
                  <span className={`dot ${onlineWord(r.online)}`} aria-hidden="true" />
                  <span className="fleet-id">{r.id}</span>
                  <span className="fleet-robot dim">{r.robot}</span>
                  <span className="fleet-online">{onlineWord(r.online)}</span>
                  <span className="fleet-state" data-testid={`fleet-state-${r.id}`}>
                    {r.state}
                    {r.state ? ' · ' : ''}
                    {r.holder ? `held by ${r.holder}` : 'nobody holds it'}
                  </span>
                  <span
                    className={`badge ${r.level}`}
                    title={[
                      r.alarm || LEVEL_WORDS[r.level],
                      r.warning,
                      r.error && `last error: ${r.error}`,
                    ]
                      .filter(Boolean)
                      .join('\n')}
                    data-testid={`fleet-alarm-${r.id}`}
                  >
                    {LEVEL_WORDS[r.level]}
                    {r.alarm ? `: ${r.alarm}` : ''}
                    {r.warning ? ` · early warning: ${r.warning}` : ''}
                  </span>
                  <PoseBars joints={r.joints} id={r.id} />
                </button>
              </li>
            ))}
          </ul>
        </details>
      )}
    </section>
  );
}
