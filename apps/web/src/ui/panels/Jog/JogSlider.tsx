import { useEffect, useId, useRef, useState, type ReactNode } from 'react';
import type { SliderSpec } from '../../../core/robots/robotSpec.ts';

/** After the user last changed a slider, it follows the arm again after this long, ms. */
const FOLLOW_AFTER_MS = 1500;

interface Props {
  spec: SliderSpec;
  /** Reported joint value, degrees or mm (NaN = unknown). */
  live: number;
  disabled: boolean;
  onJog(pwm: number): void;
  /** Shown around the slider: the hold-to-jog − / + buttons (./HoldButtons.tsx). */
  hold?: { minus: ReactNode; plus: ReactNode };
}

/**
 * One joint's slider. It shows where the arm is (whoever moved it: this slider, a command, a
 * plan, another operator), except while it is held down and for `FOLLOW_AFTER_MS` after the
 * user last changed it (so it does not jump back while the arm catches up). Focus alone does
 * not hold it.
 */
export function JogSlider({ spec, live, disabled, onJog, hold }: Props) {
  const id = useId();
  const [deg, setDeg] = useState(0);
  const touchedAt = useRef(-Infinity);
  const held = useRef(false);
  /** Bumped when the user lets go, so the slider catches up with an arm that did not move. */
  const [released, setReleased] = useState(0);

  useEffect(() => {
    if (Number.isNaN(live) || held.current) return;
    const wait = touchedAt.current + FOLLOW_AFTER_MS - performance.now();
    if (wait > 0) {
      const timer = setTimeout(() => setReleased((n) => n + 1), wait);
      return () => clearTimeout(timer);
    }
    const v = Math.min(spec.max, Math.max(spec.min, live));
    setDeg(Math.min(spec.max, Math.max(spec.min, Math.round(v / spec.step) * spec.step)));
  }, [live, released, spec.min, spec.max, spec.step]);

  const letGo = () => {
    held.current = false;
    touchedAt.current = performance.now();
    setReleased((n) => n + 1);
  };

  const pwm = spec.pwmFromValue(deg);
  const unit = spec.unit === 'deg' ? '°' : ' mm';
  return (
    <div className="jog-row">
      <div className="jog-head">
        <label htmlFor={id}>{spec.name}</label>
        <span className="jog-value" aria-hidden="true">
          {deg}
          {unit}{' '}
          <span className="dim">
            · live {Number.isNaN(live) ? '—' : `${live.toFixed(1)}${unit}`}
          </span>
        </span>
      </div>
      <div className="jog-line">
        {hold?.minus}
        <input
          id={id}
          type="range"
          min={spec.min}
          max={spec.max}
          step={spec.step}
          value={deg}
          disabled={disabled}
          onPointerDown={() => {
            held.current = true;
            window.addEventListener('pointerup', letGo, { once: true });
            window.addEventListener('pointercancel', letGo, { once: true });
          }}
          aria-valuetext={`${deg} ${spec.unit === 'deg' ? 'degrees' : 'millimetres'}, ${pwm} microseconds`}
          onChange={(e) => {
            const next = Number(e.currentTarget.value);
            touchedAt.current = performance.now();
            setDeg(next);
            onJog(spec.pwmFromValue(next));
          }}
        />
        {hold?.plus}
      </div>
    </div>
  );
}
