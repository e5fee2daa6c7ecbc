/**
 * The Jog panel's folded gamepad section: which gamepad is in use, whether its enabling button
 * is held, and the mapping (sticks → joints, enabling button, stop button), editable and saved in
 * localStorage (../../../core/jog/gamepadMapping.ts).
 */
import { useState } from 'react';
import { useSampled } from '../../hud/useSampled.ts';
import type { GamepadJog } from '../../../core/jog/GamepadJog.ts';
import { isTipAxis, TIP_AXES } from '../../../core/jog/tipHold.ts';
import {
  AXIS_NAMES,
  BUTTON_NAMES,
  DEFAULT_GAMEPAD_MAPPING,
  parseGamepadMapping,
  type GamepadMapping,
} from '../../../core/jog/gamepadMapping.ts';

interface Props {
  gamepad: GamepadJog;
  joints: readonly string[];
}

const buttonName = (i: number) => BUTTON_NAMES[i] ?? `Button ${i}`;
const axisName = (i: number) => AXIS_NAMES[i] ?? `Axis ${i}`;

export function GamepadSection({ gamepad, joints }: Props) {
  const state = useSampled(() => ({ ...gamepad.state, problem: gamepad.mappingProblem }));
  const [mapping, setMapping] = useState<GamepadMapping>(() => structuredClone(gamepad.mapping));
  const [error, setError] = useState('');

  const apply = (next: GamepadMapping) => {
    setMapping(next);
    const r = parseGamepadMapping(next);
    if (!r.ok) return setError(`Not saved: ${r.error}.`);
    setError('');
    gamepad.setMapping(r.mapping);
  };
  const buttons = (value: number, onChange: (v: number) => void, label: string) => (
    <select aria-label={label} value={value} onChange={(e) => onChange(Number(e.target.value))}>
      {BUTTON_NAMES.map((_, i) => (
        <option key={i} value={i}>
          {buttonName(i)}
        </option>
      ))}
    </select>
  );

  return (
    <details className="jog-gamepad" data-testid="gamepad-section">
      <summary>
        Gamepad{' '}
        <span className="dim" data-testid="gamepad-state">
          {state.name
            ? `${state.name.slice(0, 40)} · ${state.enabled ? 'enabled' : `hold ${buttonName(mapping.enableButton)} to jog`}`
            : 'none connected (press a button on it)'}
        </span>
      </summary>
      {state.problem && <p className="note warn">{state.problem}</p>}
      {state.lastStop && (
        <p className="note bad" role="status" data-testid="gamepad-stopped">
          Emergency stop from the gamepad at {state.lastStop}. Release and press{' '}
          {buttonName(mapping.enableButton)} again to jog.
        </p>
      )}
      <table className="jog-mapping" data-testid="gamepad-mapping">
        <tbody>
          {mapping.axes.map((a, k) => (
            <tr key={k}>
              <th scope="row">{axisName(a.axis)}</th>
              <td>
                <select
                  aria-label={`${axisName(a.axis)} drives`}
                  value={String(a.joint)}
                  onChange={(e) => {
                    const v = e.target.value;
                    const joint = isTipAxis(v) ? v : Number(v);
                    const axes = mapping.axes.map((x, j) => (j === k ? { ...x, joint } : x));
                    apply({ ...mapping, axes });
                  }}
                >
                  <option value={-1}>nothing</option>
                  {joints.map((n, j) => (
                    <option key={j} value={j}>
                      {n}
                    </option>
                  ))}
                  {TIP_AXES.map((t) => (
                    <option key={t} value={t}>
                      Tip {t}
                    </option>
                  ))}
                </select>
              </td>
              <td>
                <label>
                  <input
                    type="checkbox"
                    checked={a.invert}
                    onChange={(e) => {
                      const axes = mapping.axes.map((x, j) =>
                        j === k ? { ...x, invert: e.target.checked } : x,
                      );
                      apply({ ...mapping, axes });
                    }}
                  />{' '}
                  invert
                </label>
              </td>
            </tr>
          ))}
          <tr>
            <th scope="row">Enable (hold)</th>
            <td colSpan={2}>
              {buttons(
                mapping.enableButton,
                (v) => apply({ ...mapping, enableButton: v }),
                'Enabling button',
              )}
            </td>
          </tr>
          <tr>
            <th scope="row">Emergency stop</th>
            <td colSpan={2}>
              {buttons(
                mapping.stopButton,
                (v) => apply({ ...mapping, stopButton: v }),
                'Emergency stop button',
              )}
            </td>
          </tr>
        </tbody>
      </table>
      {error && (
        <p className="note bad" role="alert">
          {error}
        </p>
      )}
      <button type="button" onClick={() => apply(structuredClone(DEFAULT_GAMEPAD_MAPPING))}>
        Default mapping
      </button>
    </details>
  );
}
