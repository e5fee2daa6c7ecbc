import { useEffect, useId, useRef, useState } from 'react';
import { pwmFromAngle } from '@armtwin/protocol';
import type { ServoSpec } from '@armtwin/ik';

/** After the user last touched a slider, it follows the arm again after this long, ms. */
const FOLLOW_AFTER_MS = 1500;

interface Props {
  spec: ServoSpec;
  /** Reported servo angle, degrees (NaN = unknown). */
  live: number;
  /** Commanded servo angle, degrees (NaN = none). */
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
    setDeg(Math.round(Math.min(spec.maxDeg, Math.max(spec.minDeg, shown))));
  }, [shown, spec.minDeg, spec.maxDeg]);

  const pwm = pwmFromAngle(deg, spec.polarity);
  return (
    <div className="jog-row">
      <div className="jog-head">
        <label htmlFor={id}>{spec.name}</label>
        <span className="jog-value" aria-hidden="true">
          {deg}°{' '}
          <span className="dim">· live {Number.isNaN(live) ? '—' : `${live.toFixed(1)}°`}</span>
        </span>
      </div>
      <input
        id={id}
        type="range"
        min={spec.minDeg}
        max={spec.maxDeg}
        step={1}
        value={deg}
        disabled={disabled}
        aria-valuetext={`${deg} degrees, ${pwm} microseconds`}
        onChange={(e) => {
          const next = Number(e.currentTarget.value);
          touchedAt.current = performance.now();
          setDeg(next);
          onJog(pwmFromAngle(next, spec.polarity));
        }}
      />
    </div>
  );
}
