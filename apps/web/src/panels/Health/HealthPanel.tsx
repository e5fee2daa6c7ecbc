/**
 * Health: per-servo temperature and voltage, live strip charts (uPlot, outside React), and each
 * servo's level per PROTOCOL.md §5 — normal; warning in orange; critical in flashing red with a
 * prompt to cut the power; below 6.5 V in red — also stated in words for assistive technology.
 */
import { useEffect, useRef } from 'react';
import { useHud } from '../../hud/HudContext.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { servoHealth } from '../../store/healthWords.ts';
import { HealthCharts } from './HealthCharts.ts';
import { SERVO_COLOURS } from './constants.ts';

export function HealthPanel() {
  const { store } = useHud();
  const tempRef = useRef<HTMLDivElement>(null);
  const voltRef = useRef<HTMLDivElement>(null);

  useEffect(() => {
    if (!tempRef.current || !voltRef.current) return;
    const charts = new HealthCharts(store, tempRef.current, voltRef.current);
    return () => charts.dispose();
  }, [store]);

  const rows = useSampled(() =>
    store.opts.arm.servos.map((spec, i) => {
      const t = store.temp[i]!;
      const mv = store.mv[i]!;
      return { id: spec.id, name: spec.name, t, mv, ...servoHealth(spec.name, t, mv) };
    }),
  );
  const critical = rows.filter((r) => r.temperatureLevel === 'critical');
  const attention = rows.filter((r) => r.level === 'warning' || r.level === 'critical');

  return (
    <section className="panel health" aria-labelledby="health-title">
      <h2 id="health-title">Health</h2>
      {critical.length > 0 && (
        <div className="alarm" role="alert">
          Overheating: {critical.map((r) => `${r.name} ${Math.round(r.t)} °C`).join(', ')}. Cut the
          power to the arm now.
        </div>
      )}
      <table className="health-table">
        <thead>
          <tr>
            <th scope="col">Servo</th>
            <th scope="col">Temp</th>
            <th scope="col">Supply</th>
            <th scope="col">Level</th>
          </tr>
        </thead>
        <tbody>
          {rows.map((r, i) => (
            <tr
              key={r.id}
              className={`level-${r.level} temp-${r.temperatureLevel} volt-${r.voltageLevel}`}
              data-testid={`health-${r.id}`}
            >
              <th scope="row">
                <span
                  className="swatch"
                  style={{ background: SERVO_COLOURS[i] }}
                  aria-hidden="true"
                />
                {r.name}
              </th>
              <td className="temp">{Number.isNaN(r.t) ? '—' : `${Math.round(r.t)} °C`}</td>
              <td className="volt">{Number.isNaN(r.mv) ? '—' : `${(r.mv / 1000).toFixed(2)} V`}</td>
              <td className="level">
                <span aria-hidden="true">{r.level === 'unknown' ? '—' : r.level}</span>
                <span className="visually-hidden">{r.words}</span>
              </td>
            </tr>
          ))}
        </tbody>
      </table>
      <div className="visually-hidden" aria-live="polite" data-testid="health-announcer">
        {rows.every((r) => r.level === 'unknown')
          ? 'No health data yet.'
          : attention.length === 0
            ? 'All servos normal.'
            : attention.map((r) => r.words).join(' ')}
      </div>
      <div className="chart-label">Temperature °C</div>
      <div ref={tempRef} className="chart" />
      <div className="chart-label">Supply V</div>
      <div ref={voltRef} className="chart" />
    </section>
  );
}
