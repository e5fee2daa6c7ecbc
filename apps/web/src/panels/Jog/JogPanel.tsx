/**
 * Jog: one slider per servo of the arm's profile, named after its joint ("Base", "Shoulder", …),
 * in degrees (millimetres for a prismatic axis) within the joint's limits (so the HUD never sends
 * an out-of-limit pulse). Dragging or arrow keys
 * publish `#IIIPppppTtttt!` (`#IIIA±ddd.ddTtttt!` for a servo that speaks angles), coalesced by ArmLink to ≤ 20 per second per servo. Disabled while
 * the data is stale or the broker is not connected. A jog that would take the hand (or a joint)
 * below the floor is not sent, and says so. Each slider follows the arm when not in use.
 */
import { useState } from 'react';
import { checkFloorMove } from '@armtwin/motion';
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
    };
  });
  const [refusal, setRefusal] = useState('');

  /** Servo i to `pwm`, unless that pose would take the hand or a joint below the floor. */
  const jog = (i: number, id: number, pwm: number) => {
    const motion = robots.active.motion;
    const from = Array.from(store.pwm);
    if (motion && from.length === motion.ids.length && from.every(Number.isFinite)) {
      const to = [...from];
      to[i] = pwm;
      const c = checkFloorMove(motion, from, to);
      if (!c.ok) return setRefusal(`Not sent: ${c.message}.`);
    }
    setRefusal('');
    link.jog(id, pwm);
  };
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
          disabled={!snap.enabled}
          onJog={(pwm) => jog(i, spec.id, pwm)}
        />
      ))}
      {refusal && (
        <p className="note bad" role="alert" data-testid="jog-refusal">
          {refusal}
        </p>
      )}
    </section>
  );
}

const round1 = (v: number) => Math.round(v * 10) / 10;
