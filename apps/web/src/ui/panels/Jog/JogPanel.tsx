/**
 * Jog: one slider per servo of the arm's profile, named after its joint ("Base", "Shoulder", …),
 * in degrees (millimetres for a prismatic axis) within the joint's limits (so the HUD never sends
 * an out-of-limit pulse). Dragging or arrow keys
 * publish `#IIIPppppTtttt!` (`#IIIA±ddd.ddTtttt!` for a servo that speaks angles), coalesced by ArmLink to ≤ 20 per second per servo. Disabled while
 * the data is stale or the broker is not connected. A slider's move is a hold of one target
 * (HoldJog.jogTo, core/jog/): one that would take the hand (or a joint) below the floor, or a
 * link into a keep-out zone, is not sent, and says so. Each slider follows the arm when not in use.
 * Hold-to-jog: the − / + beside each slider, the hold keys and a gamepad move a joint only while
 * held, at the chosen speed (core/jog/HoldJog.ts, core/jog/GamepadJog.ts).
 */
import { useState } from 'react';
import { useArm, useLink, useSession, useRobots, useJog, useModes } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { JogSlider } from './JogSlider.tsx';
import { HoldButton } from './HoldButton.tsx';
import { GamepadSection } from './GamepadSection.tsx';
import { DEFAULT_HOLD_KEYS, keyLabel } from '../../../core/jog/holdJogMath.ts';
import { TIP_AXES } from '../../../core/jog/tipHold.ts';

export function JogPanel() {
  const store = useArm();
  const link = useLink();
  const session = useSession();
  const robots = useRobots();
  const holdJog = useJog();
  const modes = useModes();
  // The arm the sliders drive and show: the model copy in Model mode, else the arm.
  const driven = () => modes.driven(store);
  const { hold, gamepad } = holdJog;
  const servos = robots.active.spec.sliders;
  const snap = useSampled(() => {
    const now = performance.now();
    const arm = driven();
    return {
      enabled: link.mayMove && store.connection === 'connected' && !arm.isStale(now),
      allowed: link.permissions.command,
      heldBy: link.control.heldBy,
      live: Array.from(arm.pwm, (p, i) => {
        const spec = servos[i];
        if (!spec) return NaN;
        return round1(spec.speaksAngle ? spec.valueFromAngle(arm.angle[i]!) : spec.valueFromPwm(p));
      }),
    };
  });
  const [refusal, setRefusal] = useState('');
  const holding = useSampled(() => ({ held: hold.held(), refusal: hold.refusal }), 100);
  const [speed, setSpeed] = useState(hold.speed);

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
            {snap.heldBy
              ? `Controlled by ${snap.heldBy}: ask for control in the Fleet panel.`
              : 'Jogging disabled until fresh status arrives.'}
          </p>
        )
      )}
      {servos.map((spec, i) => (
        <JogSlider
          key={spec.id}
          spec={spec}
          live={snap.live[i] ?? NaN}
          disabled={!snap.enabled}
          onJog={(pwm) => setRefusal(hold.jogTo(i, pwm))}
          hold={{
            minus: (
              <HoldButton
                hold={hold}
                index={i}
                rate={-1}
                name={spec.name}
                disabled={!snap.enabled}
              />
            ),
            plus: (
              <HoldButton
                hold={hold}
                index={i}
                rate={1}
                name={spec.name}
                disabled={!snap.enabled}
              />
            ),
          }}
        />
      ))}
      <div className="jog-hold-bar">
        <label>
          Hold speed{' '}
          <select
            value={speed}
            data-testid="hold-speed"
            onChange={(e) => {
              hold.setSpeed(Number(e.target.value));
              setSpeed(hold.speed);
            }}
          >
            {hold.opts.speeds.map((v) => (
              <option key={v} value={v}>
                {v} °/s (mm/s)
              </option>
            ))}
          </select>
        </label>
        <span className="dim" data-testid="hold-state">
          {holding.held.length > 0
            ? `moving: ${holding.held.map((i) => (typeof i === 'number' ? (servos[i]?.name ?? i) : `tip ${i}`)).join(', ')}`
            : 'hold − / + to move'}
        </span>
      </div>
      <details className="jog-keys">
        <summary>Hold keys</summary>
        <p className="dim" data-testid="hold-keys">
          {servos
            .slice(0, DEFAULT_HOLD_KEYS.plus.length)
            .map(
              (s, i) =>
                `${s.name}: ${keyLabel(DEFAULT_HOLD_KEYS.minus[i]!)} − / ${keyLabel(DEFAULT_HOLD_KEYS.plus[i]!)} +`,
            )
            .join(' · ')}
          . A joint moves while its key is held; Esc stops everything.
        </p>
      </details>
      <details className="jog-tip" data-testid="tip-hold">
        <summary>Tip x, y, z</summary>
        <p className="dim">
          Moves the tool tip along the base frame&apos;s axes at the hold speed in mm/s, its pitch
          kept, through the IK.
        </p>
        {TIP_AXES.map((a) => (
          <div className="jog-tip-row" key={a}>
            <HoldButton
              hold={hold}
              index={a}
              rate={-1}
              name={`tip ${a}`}
              disabled={!snap.enabled}
            />
            <span className="jog-tip-axis">{a}</span>
            <HoldButton hold={hold} index={a} rate={1} name={`tip ${a}`} disabled={!snap.enabled} />
          </div>
        ))}
      </details>
      <GamepadSection gamepad={gamepad} joints={servos.map((s) => s.name)} />
      {holding.refusal && (
        <p className="note bad" role="alert" data-testid="hold-refusal">
          {holding.refusal}
        </p>
      )}
      {refusal && (
        <p className="note bad" role="alert" data-testid="jog-refusal">
          {refusal}
        </p>
      )}
    </section>
  );
}

const round1 = (v: number) => Math.round(v * 10) / 10;
