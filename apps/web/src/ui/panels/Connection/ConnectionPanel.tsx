/**
 * Connection settings: broker URL (or an ordered, comma-separated list of them), arm id, username, password, how the twin is drawn
 * (predicted, interpolated, newest report). "Connect" checks them, saves
 * all but the password in localStorage and reconnects. Defaults: same-origin ws(s)://host/mqtt
 * and arm1; the URL query (?broker=…&arm=…) overrides both.
 */
import { useState, type FormEvent } from 'react';
import { useSettings, useReconnect } from '../../hud/HudParts.ts';
import { saveSettings, validateSettings } from '../../../core/config/settings.ts';
import { TWIN_MODES, type TwinMode } from '../../../core/store/TwinPredictor.ts';

const TWIN_WORDS: Record<TwinMode, string> = {
  predict: 'Predicted (where the arm is now)',
  interpolate: 'Interpolated (the seed’s tween)',
  newest: 'Newest report as it came',
};

export function ConnectionPanel() {
  const settings = useSettings();
  const { reconnect } = useReconnect();
  const [form, setForm] = useState(settings);
  const [error, setError] = useState('');

  const submit = (e: FormEvent) => {
    e.preventDefault();
    const problem = validateSettings(form);
    setError(problem ?? '');
    if (problem) return;
    saveSettings(form);
    reconnect(form);
  };
  const field = (
    key: 'brokerUrl' | 'armId' | 'username' | 'password',
    label: string,
    type = 'text',
  ) => (
    <label className="field">
      <span>{label}</span>
      <input
        type={type}
        value={form[key]}
        autoComplete={type === 'password' ? 'current-password' : 'off'}
        spellCheck={false}
        onChange={(e) => setForm({ ...form, [key]: e.currentTarget.value })}
      />
    </label>
  );

  return (
    <details className="panel connection">
      <summary>
        <h2>Connection</h2>
        <span className="dim">
          {settings.brokerUrl} · {settings.armId}
        </span>
      </summary>
      <form onSubmit={submit}>
        {field('brokerUrl', 'Broker URLs')}
        <p className="note dim" id="broker-list-hint">
          One ws:// or wss:// URL, or several separated by commas: the first is preferred, the
          others are fall-backs the page moves to when it loses its broker.
        </p>
        {field('armId', 'Arm id')}
        {field('username', 'Username')}
        {field('password', 'Password', 'password')}
        <label className="field">
          <span>Twin</span>
          <select
            value={form.twinMode}
            onChange={(e) => setForm({ ...form, twinMode: e.currentTarget.value as TwinMode })}
          >
            {TWIN_MODES.map((m) => (
              <option key={m} value={m}>
                {TWIN_WORDS[m]}
              </option>
            ))}
          </select>
        </label>
        {error && (
          <p className="note bad" role="alert">
            {error}
          </p>
        )}
        <button type="submit">Connect</button>
      </form>
    </details>
  );
}
