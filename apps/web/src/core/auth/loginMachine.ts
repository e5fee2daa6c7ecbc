/**
 * The page's log-in states, as a pure reducer (no timers, no sockets):
 *
 *   checking ──role──▶ connecting ──connected──▶ signed-in
 *      ▲                   │ refused                 │ refused (e.g. the password changed)
 *      │ start             ▼                         ▼
 *      └──────────── needs-login ◀───────────────────┘
 *
 * `start` begins every attempt (anonymous first, then with what the form sends); `refused` is
 * CONNACK 4/5 from the broker. `invalid` (a bad arm id in the URL) ends it: nothing connects.
 */
import type { Access } from './roles.ts';

export type LoginState =
  | { phase: 'checking'; username: string }
  | { phase: 'connecting'; username: string; access: Access }
  | { phase: 'signed-in'; username: string; access: Access }
  | { phase: 'needs-login'; username: string; error: string }
  | { phase: 'invalid'; error: string };

export type LoginEvent =
  | { type: 'start'; username: string }
  | { type: 'role'; access: Access }
  | { type: 'connected' }
  | { type: 'refused'; message: string }
  | { type: 'invalid'; error: string };

export const INITIAL_LOGIN: LoginState = { phase: 'checking', username: '' };

export function loginReducer(state: LoginState, event: LoginEvent): LoginState {
  if (state.phase === 'invalid') return state;
  switch (event.type) {
    case 'invalid':
      return { phase: 'invalid', error: event.error };
    case 'start':
      return { phase: 'checking', username: event.username };
    case 'role':
      return state.phase === 'checking'
        ? { phase: 'connecting', username: state.username, access: event.access }
        : state;
    case 'connected':
      return state.phase === 'connecting'
        ? { phase: 'signed-in', username: state.username, access: state.access }
        : state;
    case 'refused': {
      if (state.phase === 'needs-login') return state;
      const username = state.username;
      return {
        phase: 'needs-login',
        username,
        error: username
          ? `Log-in refused for "${username}": ${event.message}.`
          : 'This broker needs a log-in.',
      };
    }
  }
}

/** The role the page acts on now, or null (not connected with a known role). */
export function currentAccess(s: LoginState): Access | null {
  return s.phase === 'connecting' || s.phase === 'signed-in' ? s.access : null;
}
