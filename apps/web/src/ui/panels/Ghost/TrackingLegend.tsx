/**
 * Tracking error on the arm: the switch that paints each link by its joint's commanded-vs-
 * reported error (scene/TrackingPaint.ts), the colour ramp with its thresholds, and each joint's
 * error in degrees (the numbers behind the colours). Painting is on by default once something
 * has been commanded ('auto'); the switch makes it on or off for good.
 */
import { useState } from 'react';
import { useArm } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import type { TrackingLevel } from '../../../core/store/trackingError.ts';

const hex = (c: number) => `#${c.toString(16).padStart(6, '0')}`;

const LEVEL_WORDS: Record<TrackingLevel, string> = {
  none: 'nothing commanded',
  ok: 'tracking',
  warn: 'lagging',
  error: 'off its command',
};

export function TrackingLegend() {
  const store = useArm();
  const [, changed] = useState(0);
  const t = useSampled(() => {
    const tr = store.tracking;
    return {
      active: tr.active,
      joints: store.opts.arm.servos.map((s, i) => ({
        id: s.id,
        name: s.name,
        level: tr.levels[i] ?? 'none',
        err: Math.round((tr.errorDeg[i] ?? NaN) * 10) / 10,
      })),
    };
  });
  const o = store.tracking.opts;
  const c = o.colours;
  return (
    <div className="tracking" data-testid="tracking">
      <label className="check">
        <input
          type="checkbox"
          checked={store.tracking.active}
          onChange={(e) => {
            store.tracking.setSetting(e.currentTarget.checked ? 'on' : 'off');
            changed((n) => n + 1);
          }}
        />
        Paint tracking error on the arm
      </label>
      <div
        className="tracking-ramp"
        role="img"
        aria-label={`Colour ramp: green below ${o.okDeg}°, amber to red up to ${o.errorDeg}°, red from ${o.errorDeg}°`}
        style={{
          background: `linear-gradient(to right, ${hex(c.ok)} 0 30%, ${hex(c.warn)} 30%, ${hex(c.error)} 85%, ${hex(c.error)})`,
        }}
      />
      <p className="dim small-print tracking-scale" aria-hidden="true">
        <span>0°</span>
        <span>{o.okDeg}°</span>
        <span>≥ {o.errorDeg}°</span>
      </p>
      {store.tracking.active && (
        <ul className="tracking-joints">
          {t.joints.map((j) => (
            <li
              key={j.id}
              className={`tracking-${j.level}`}
              data-testid={`tracking-${j.id}`}
              data-level={j.level}
              title={LEVEL_WORDS[j.level]}
            >
              <span className="tracking-dot" aria-hidden="true" />
              {j.name}:{' '}
              {Number.isFinite(j.err) ? `${j.err.toFixed(1)}° (${LEVEL_WORDS[j.level]})` : '—'}
            </li>
          ))}
        </ul>
      )}
    </div>
  );
}
