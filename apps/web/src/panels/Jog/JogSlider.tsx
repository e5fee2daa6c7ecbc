import { useEffect, useId, useRef, useState } from 'react';
import type { SliderSpec } from '../../robots/robotSpec.ts';

/** After the user last touched a slider, it follows the arm again after this long, ms. */
const FOLLOW_AFTER_MS = 1500;

interface Props {
  spec: SliderSpec;
  /** Reported joint value, degrees or mm (NaN = unknown). */
  live: number;
  /** Commanded joint value, degrees or mm (NaN = none). */
  commanded: number;
  disabled: boolean;
  onJog(pwm: number): void;
}

export function JogSlider({ spec, live, commanded, disabled, onJog }: Props) {
  const id = useId();
  const [deg, setDeg] = useState(0);
  const touchedAt = useRef(-Infinity);
  const shown = Number.isNaN(commanded) ? live : commanded;

  // Follow the commanded (else live) angle unless the user is using the slider.
  useEffect(() => {
    if (Number.isNaN(shown) || performance.now() - touchedAt.current < FOLLOW_AFTER_MS) return;
    const v = Math.min(spec.max, Math.max(spec.min, shown));
    setDeg(Math.min(spec.max, Math.max(spec.min, Math.round(v / spec.step) * spec.step)));
  }, [shown, spec.min, spec.max, spec.step]);

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
      <input
        id={id}
        type="range"
        min={spec.min}
        max={spec.max}
        step={spec.step}
        value={deg}
        disabled={disabled}
        aria-valuetext={`${deg} ${spec.unit === 'deg' ? 'degrees' : 'millimetres'}, ${pwm} microseconds`}
        onChange={(e) => {
          const next = Number(e.currentTarget.value);
          touchedAt.current = performance.now();
          setDeg(next);
          onJog(spec.pwmFromValue(next));
        }}
      />
    </div>
  );
}
