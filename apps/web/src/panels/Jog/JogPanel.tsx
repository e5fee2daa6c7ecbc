/**
 * Jog: one slider per servo of the arm's profile, named after its joint ("Base", "Shoulder", …),
 * in degrees (millimetres for a prismatic axis) within the joint's limits (so the HUD never sends
 * an out-of-limit pulse). Dragging or arrow keys
 * publish `#IIIPppppTtttt!` (`#IIIA±ddd.ddTtttt!` for a servo that speaks angles), coalesced by ArmLink to ≤ 20 per second per servo. Disabled while
 * the data is stale or the broker is not connected.
 */
import { useHud } from '../../hud/HudContext.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { JogSlider } from './JogSlider.tsx';

export function JogPanel() {
  const { store, link, session, robots } = useHud();
  const servos = robots.active.spec.sliders;
  const snap = useSampled(() => {
    const now = performance.now();
    return {
      enabled: link.permissions.command && store.connection === 'connected' && !store.isStale(now),
      allowed: link.permissions.command,
      live: Array.from(store.pwm, (p, i) => {
        const spec = servos[i];
        if (!spec) return NaN;
        return round1(
          spec.speaksAngle ? spec.valueFromAngle(store.angle[i]!) : spec.valueFromPwm(p),
        );
      }),
      commanded: Array.from(store.commandedPwm, (p, i) =>
        round1(servos[i]?.valueFromPwm(p) ?? NaN),
      ),
    };
  });
  return (
    <section className="panel jog" aria-labelledby="jog-title">
      <h2 id="jog-title">Jog</h2>
      {!snap.allowed ? (
        <p className="note warn" role="status" data-testid="jog-disabled">
          {session.permissions?.reason || 'Jogging disabled until the role is known.'}
        </p>
      ) : (
        !snap.enabled && (
          <p className="note warn" role="status" data-testid="jog-disabled">
            Jogging disabled until fresh status arrives.
          </p>
        )
      )}
      {servos.map((spec, i) => (
        <JogSlider
          key={spec.id}
          spec={spec}
          live={snap.live[i] ?? NaN}
          commanded={snap.commanded[i] ?? NaN}
          disabled={!snap.enabled}
          onJog={(pwm) => link.jog(spec.id, pwm)}
        />
      ))}
    </section>
  );
}

const round1 = (v: number) => Math.round(v * 10) / 10;
