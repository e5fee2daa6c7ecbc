/**
 * Who this page is signed in as, and the log-in form. The page tries without credentials first
 * (the local demo); when the broker refuses, the form appears. The password goes to the broker
 * and `/api/whoami` only, and is kept in memory, never in localStorage. A viewer (or any role
 * that may not move the arm) is told so here, in words.
 */
import { useState, type FormEvent } from 'react';
import { useSession, useSettings, useReconnect } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { saveSettings } from '../../../core/config/settings.ts';
import { sessionWords } from './words.ts';

export function LoginPanel() {
  const session = useSession();
  const settings = useSettings();
  const { reconnect } = useReconnect();
  const state = useSampled(() => session.state);
  const permissions = useSampled(() => session.permissions);
  const error = useSampled(() => session.error);
  const [open, setOpen] = useState(false);
  const [username, setUsername] = useState(settings.username);
  const [password, setPassword] = useState('');

  const submit = (e: FormEvent) => {
    e.preventDefault();
    const next = { ...settings, username: username.trim(), password };
    setPassword('');
    setOpen(false);
    saveSettings(next); // user name only
    reconnect(next);
  };

  if (state.phase === 'invalid') {
    return (
      <section className="panel login" aria-labelledby="login-title">
        <h2 id="login-title">Not connected</h2>
        <p className="note bad" role="alert" data-testid="query-error">
          {state.error}
        </p>
      </section>
    );
  }

  const words = sessionWords(state, permissions);
  const showForm = state.phase === 'needs-login' || open;
  return (
    <section className="panel login" aria-labelledby="login-title">
      <h2 id="login-title">Account</h2>
      <p data-testid="signed-in-as" className="dim">
        {words.who}
      </p>
      {words.reason && (
        <p className="note warn" role="status" data-testid="role-reason">
          {words.reason}
        </p>
      )}
      {state.phase === 'needs-login' && state.error && (
        <p className="note bad" role="alert" data-testid="login-error">
          {state.error}
        </p>
      )}
      {error && (
        <p className="note bad" role="alert">
          {error}
        </p>
      )}
      {showForm ? (
        <form onSubmit={submit} aria-label="Log in">
          <label className="field">
            <span>Username</span>
            <input
              value={username}
              autoComplete="username"
              spellCheck={false}
              onChange={(e) => setUsername(e.currentTarget.value)}
            />
          </label>
          <label className="field">
            <span>Password</span>
            <input
              type="password"
              value={password}
              autoComplete="current-password"
              onChange={(e) => setPassword(e.currentTarget.value)}
            />
          </label>
          <button type="submit">Log in</button>
        </form>
      ) : (
        state.phase === 'signed-in' && (
          <button type="button" onClick={() => setOpen(true)}>
            Log in as another user
          </button>
        )
      )}
    </section>
  );
}
