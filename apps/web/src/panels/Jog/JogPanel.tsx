/**
 * Jog: one slider per servo, named after its joint ("Base", "Shoulder", …), in degrees within
 * the servo's limits (so the HUD never sends an out-of-limit pulse). Dragging or arrow keys
 * publish `#IIIPppppTtttt!`, coalesced by ArmLink to ≤ 20 per second per servo. Disabled while
 * the data is stale or the broker is not connected.
 */
import { useHud } from '../../hud/HudContext.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { JogSlider } from './JogSlider.tsx';
import { angleFromPwm } from '@armtwin/protocol';

export function JogPanel() {
  const { store, link } = useHud();
  const servos = store.opts.arm.servos;
  const snap = useSampled(() => {
    const now = performance.now();
    return {
      enabled: store.connection === 'connected' && !store.isStale(now),
      live: Array.from(store.pwm, (p, i) => round1(angleFromPwm(p, servos[i]!.polarity))),
      commanded: Array.from(store.commandedPwm, (p, i) =>
        round1(angleFromPwm(p, servos[i]!.polarity)),
      ),
    };
  });
  return (
    <section className="panel jog" aria-labelledby="jog-title">
      <h2 id="jog-title">Jog</h2>
      {!snap.enabled && (
        <p className="note warn" role="status">
          Jogging disabled until fresh status arrives.
        </p>
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
