/**
 * Calibrate: a folded panel, shown only for an arm with bus servos (profile `units: "angle"`),
 * holding the bus arm's torque switch and the calibration wizard (../../../core/calibration/CalibrationSession.ts) for
 * one joint at a time: zero, direction, travel, then the result saved to the robot's profile
 * through `armtwin up` (../../../core/calibration/saveCalibration.ts). The ghost shows each step's pose while the panel
 * is open. An operator's right; the emergency stop stays where it is and wins over any jog.
 */
import { useEffect, useState } from 'react';
import type { ServoCalibrationFields } from '@armtwin/robot';
import { useRobots, useLink, useSettings, useCalibration, useSession } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { TorqueControl } from '../Torque/TorqueControl.tsx';
import { CalibrationReview } from './CalibrationReview.tsx';
import { saveCalibration } from '../../../core/calibration/saveCalibration.ts';
import { DIRECTION_LEAN_DEG } from '../../../core/calibration/CalibrationSession.ts';
import './calibration.css';

const JOGS = [-10, -1, 1, 10] as const;

const STEP_TEXT = {
  zero: 'Step 1 of 3, zero. The ghost shows the joint at its zero. Jog the real joint slowly until it stands as the ghost does.',
  direction: `Step 2 of 3, direction. The ghost leans the joint ${DIRECTION_LEAN_DEG}° its positive way. Move the real joint the same way, a few degrees or more.`,
  range:
    'Step 3 of 3, limits. Take the joint to both ends of its safe travel: jog it, or turn torque off and move it by hand. The ghost shows the joint as the new calibration reads it.',
  review: 'Check: the ghost should stand where the real joint is. Save to write it to the profile.',
} as const;

const RECORD_LABEL = {
  zero: 'Zero is here',
  direction: 'It leans like the ghost',
  range: 'Travel recorded',
  review: '',
} as const;

const sameFields = (
  s: { polarity: number; offset: number; min: number; max: number } | undefined,
  f: ServoCalibrationFields,
) =>
  !!s && s.polarity === f.polarity && s.offset === f.offset && s.min === f.min && s.max === f.max;

export function CalibrationPanel() {
  const robots = useRobots();
  const link = useLink();
  const settings = useSettings();
  const wizard = useCalibration();
  const session = useSession();
  const profile = robots.active.spec.profile;
  const bus = profile.servos
    .map((s, i) => ({ s, i }))
    .filter(({ s }) => s.units === 'angle' && s.type === 'revolute');
  const [, setTick] = useState(0);
  const redraw = () => setTick((t) => t + 1);
  const [error, setError] = useState('');
  const [saved, setSaved] = useState<{
    robot: string;
    fields: ServoCalibrationFields;
    backup: string;
  } | null>(null);
  const snap = useSampled(() => ({
    allowed: link.permissions.command,
    reading: wizard.reading(),
    low: wizard.low,
    high: wizard.high,
    // the wizard restarted on another robot (below)
    robot: wizard.profile?.name,
    index: wizard.index,
  }));

  // A new arm or robot: the wizard starts over on its first bus servo.
  const first = bus[0]?.i ?? -1;
  useEffect(() => {
    if (first >= 0 && wizard.profile?.name !== profile.name) wizard.begin(profile, first);
  }, [profile, first, wizard]);
  useEffect(() => {
    const stopped = () => wizard.stopped();
    link.stopListeners.add(stopped);
    return () => void link.stopListeners.delete(stopped);
  }, [link, wizard]);
  useEffect(() => () => wizard.setOpen(false), [wizard]);

  if (bus.length === 0) return null;
  const servo = wizard.servo;
  const done = saved?.robot === profile.name ? saved : null;
  const inForce = done && sameFields(profile.servos[wizard.index], done.fields);
  const act = (msg: string) => {
    setError(msg);
    redraw();
  };
  const save = async (fields: ServoCalibrationFields) => {
    setError('');
    const r = await saveCalibration(settings, profile.name, fields);
    if (r.ok) wizard.markSaved();
    if (r.ok) setSaved({ robot: profile.name, fields, backup: r.backup });
    else setError(r.error);
  };

  return (
    <details
      className="panel calibration"
      data-testid="calibration"
      onToggle={(e) => wizard.setOpen(e.currentTarget.open)}
    >
      <summary>
        <h2>Calibrate</h2> <span className="dim">bus servos: torque, zero, direction, limits</span>
      </summary>
      {!snap.allowed ? (
        <p className="note warn" role="status">
          {session.permissions?.reason || 'Calibrating is for operators.'}
        </p>
      ) : (
        <>
          <TorqueControl onSent={() => wizard.stopped()} />
          <label className="calibration-joint">
            Joint{' '}
            <select
              value={wizard.index}
              onChange={(e) => {
                wizard.begin(profile, Number(e.currentTarget.value));
                setSaved(null);
                act('');
              }}
            >
              {bus.map(({ s, i }) => (
                <option key={s.id} value={i}>
                  {s.key} {s.name}
                </option>
              ))}
            </select>
          </label>
          <p className="calibration-reading">
            servo reads{' '}
            <output data-testid="calibration-reading">
              {Number.isFinite(snap.reading) ? `${snap.reading.toFixed(2)}°` : '—'}
            </output>
          </p>
          {done ? (
            <div role="status" data-testid="calibration-saved">
              <p>
                Saved to {profile.name}/profile.json (the old one kept as {done.backup}).{' '}
                {inForce
                  ? 'In force: the gateway and the twin use it now.'
                  : 'Waiting for the gateway to take it…'}
              </p>
              {inForce && <span data-testid="calibration-in-force" hidden />}
              <button
                type="button"
                onClick={() => {
                  wizard.begin(profile, wizard.index);
                  setSaved(null);
                  act('');
                }}
              >
                Calibrate again
              </button>
            </div>
          ) : (
            <>
              <p className="calibration-step" data-testid="calibration-step">
                {STEP_TEXT[wizard.step]}
              </p>
              {wizard.step !== 'review' && (
                <div className="row" role="group" aria-label="Jog slowly">
                  {JOGS.map((d) => (
                    <button
                      key={d}
                      type="button"
                      aria-label={`Jog ${d > 0 ? '+' : '−'}${Math.abs(d)}°`}
                      onClick={() => act(wizard.jog(link, d))}
                    >
                      {d > 0 ? '+' : '−'}
                      {Math.abs(d)}°
                    </button>
                  ))}
                </div>
              )}
              {wizard.step === 'range' && (
                <p className="dim" data-testid="calibration-travel">
                  travel {snap.low.toFixed(2)}° … {snap.high.toFixed(2)}°
                </p>
              )}
              {wizard.step === 'review' && servo ? (
                <CalibrationReview
                  servo={servo}
                  result={wizard.result()}
                  onSave={(f) => void save(f)}
                  onRestart={() => {
                    wizard.begin(profile, wizard.index);
                    act('');
                  }}
                />
              ) : (
                <button
                  type="button"
                  className="primary"
                  onClick={() => act(wizard.record() ? '' : 'no reading from this servo yet')}
                >
                  {RECORD_LABEL[wizard.step]}
                </button>
              )}
            </>
          )}
          {error && (
            <p className="note error" role="alert" data-testid="calibration-error">
              {error}
            </p>
          )}
        </>
      )}
    </details>
  );
}
