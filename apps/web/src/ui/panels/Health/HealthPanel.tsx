/**
 * Health: per-servo temperature and voltage, live strip charts (uPlot, outside React), and each
 * servo's level per PROTOCOL.md §5 — normal; warning in orange; critical in flashing red with a
 * prompt to cut the power; below 6.5 V in red — also stated in words for assistive technology.
 * Beside each measured temperature, dashed, what the servo's thermal model predicts from its
 * motion; when a servo heats faster than that by a margin, an early warning before 60 °C (the
 * model is fitted from the arm's recent history by the middleware, generic before).
 */
import { useEffect, useRef, useState } from 'react';
import type { ThermalModelAnswer } from '@armtwin/api';
import { authHeaders } from '../../../core/auth/whoami.ts';
import {
  applyThermalFit,
  resetThermalFit,
  THERMAL_FIT_START,
} from '../../../core/store/thermalFit.ts';
import { HistoryApi } from '../History/historyApi.ts';
import { useArm, useSettings } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { servoHealth, thermalWarningWords } from '../../../core/store/healthWords.ts';
import { HealthCharts } from './HealthCharts.ts';
import { SERVO_COLOURS } from './constants.ts';

export function HealthPanel() {
  const store = useArm();
  const settings = useSettings();
  const { armId, apiBase, username, password } = settings;
  const armVersion = useSampled(() => store.armVersion, 1000);
  const [modelText, setModelText] = useState('Thermal model: generic (no fit loaded yet).');
  const [refits, setRefits] = useState(0);

  // The arm's own thermal models, fitted by the middleware from its history; without one (no
  // storage, no history) the generic model stays and the panel says so.
  useEffect(() => {
    const abort = new AbortController();
    resetThermalFit(store.thermal); // never another arm's (or an older range's) fit
    const api = new HistoryApi({ base: apiBase, headers: authHeaders({ username, password }) });
    void api
      .get<ThermalModelAnswer>(
        'thermal-model',
        { arm: armId, start: THERMAL_FIT_START, stop: 'now' },
        abort.signal,
      )
      .then((r) => {
        if (abort.signal.aborted) return;
        if (!r.ok) return setModelText(`Thermal model: generic (${r.error})`);
        setModelText(applyThermalFit(store.thermal, store.opts.arm.servos, r.data).text);
      });
    return () => abort.abort();
  }, [store, armId, apiBase, username, password, armVersion, refits]);
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
      const early = thermalWarningWords(spec.name, store.thermal.state(i));
      return { id: spec.id, name: spec.name, t, mv, early, ...servoHealth(spec.name, t, mv) };
    }),
  );
  const early = rows.filter((r) => r.early);
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
      {early.length > 0 && (
        <div className="early-warning" data-testid="thermal-warning">
          {/* Announced once per servo, in words that do not change with every report. */}
          <span role="alert" className="visually-hidden">
            Early warning:{' '}
            {early.map((r) => `${r.name} is heating faster than its motion explains.`).join(' ')}
          </span>
          <span aria-hidden="true">Early warning: {early.map((r) => r.early).join(' ')}</span>
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
              className={`level-${r.level} temp-${r.temperatureLevel} volt-${r.voltageLevel}${r.early ? ' heating' : ''}`}
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
                {r.early && (
                  <span className="heating-tag" aria-hidden="true">
                    {' '}
                    · heating
                  </span>
                )}
                <span className="visually-hidden">
                  {r.words}
                  {r.early && ` ${r.early}`}
                </span>
              </td>
            </tr>
          ))}
        </tbody>
      </table>
      <div className="visually-hidden" aria-live="polite" data-testid="health-announcer">
        {rows.every((r) => r.level === 'unknown')
          ? 'No health data yet.'
          : attention.length === 0 && early.length === 0
            ? 'All servos normal.'
            : [...attention.map((r) => r.words), ...early.map((r) => r.early)].join(' ')}
      </div>
      <div className="chart-label">Temperature °C (dashed: the model&apos;s prediction)</div>
      <div ref={tempRef} className="chart" />
      <div className="thermal-model" data-testid="thermal-model">
        {modelText}{' '}
        <button type="button" className="refit" onClick={() => setRefits((n) => n + 1)}>
          Refit
        </button>
      </div>
      <div className="chart-label">Supply V</div>
      <div ref={voltRef} className="chart" />
    </section>
  );
}
