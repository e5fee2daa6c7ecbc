/**
 * Connection settings: broker URL, arm id, username, password. "Connect" checks them, saves
 * all but the password in localStorage and reconnects. Defaults: same-origin ws(s)://host/mqtt
 * and arm1; the URL query (?broker=…&arm=…) overrides both.
 */
import { useState, type FormEvent } from 'react';
import { useHud } from '../../hud/HudContext.ts';
import { saveSettings, validateSettings } from '../../config/settings.ts';

export function ConnectionPanel() {
  const { settings, reconnect } = useHud();
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
        {field('brokerUrl', 'Broker URL')}
        {field('armId', 'Arm id')}
        {field('username', 'Username')}
        {field('password', 'Password', 'password')}
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
