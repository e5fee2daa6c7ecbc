/**
 * Fleet: every arm on the broker (retained `arm/+/online` and `arm/+/profile`), its robot,
 * whether it is online, and an alarm badge from its latest health reports (PROTOCOL.md §5
 * levels). Selecting one makes the HUD control it (the URL's `arm=` follows). The selected arm's
 * health comes from the store, the others' from FleetLink. Arm ids and titles are text only.
 * Who controls the selected arm is said under the heading (./ControlBar.tsx).
 */
import '../robots.css';
import { useRobots, useSettings, useArm, useReconnect } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { fleetList, healthSummary, type FleetArm } from '../../../core/robots/fleet.ts';
import { ControlBar } from './ControlBar.tsx';
import { isModelArmId, MODEL_ARM_SUFFIX } from '../../../core/link/modes.ts';

const onlineWord = (o: boolean | null) =>
  o === true ? 'online' : o === false ? 'offline' : 'unknown';
const LEVEL_WORDS = {
  normal: 'ok',
  warning: 'warning',
  critical: 'alarm',
  unknown: 'no health yet',
} as const;

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
      // The selected arm's health is in the store (FleetLink does not subscribe it twice).
      const health: Record<number, { temp: number; mv: number }> = {};
      store.opts.arm.servos.forEach((s, i) => {
        health[s.id] = { temp: store.temp[i]!, mv: store.mv[i]! };
      });
      return { ...a, ...healthSummary(health), health: {} };
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
      })),
    };
  });
  return (
    <section className="panel fleet" aria-labelledby="fleet-title">
      <h2 id="fleet-title">Fleet</h2>
      <ControlBar />
      {snap.rows.length === 0 ? (
        <p className="dim">No arms seen on the broker yet.</p>
      ) : (
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
                <span
                  className={`badge ${r.level}`}
                  title={r.alarm || LEVEL_WORDS[r.level]}
                  data-testid={`fleet-alarm-${r.id}`}
                >
                  {LEVEL_WORDS[r.level]}
                  {r.alarm ? `: ${r.alarm}` : ''}
                </span>
              </button>
            </li>
          ))}
        </ul>
      )}
    </section>
  );
}
