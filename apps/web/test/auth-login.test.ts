import { describe, expect, it } from 'vitest';
import {
  currentAccess,
  INITIAL_LOGIN,
  loginReducer,
  type LoginEvent,
  type LoginState,
} from '../src/core/auth/loginMachine.ts';
import type { Access } from '../src/core/auth/roles.ts';

const viewer: Access = { role: 'viewer', source: 'server', name: 'viewer' };
const run = (events: LoginEvent[], from: LoginState = INITIAL_LOGIN) =>
  events.reduce(loginReducer, from);

describe('login state machine', () => {
  it('anonymous first: the local demo signs in without a form', () => {
    const s = run([
      { type: 'start', username: '' },
      { type: 'role', access: { role: 'operator', source: 'demo', name: '' } },
      { type: 'connected' },
    ]);
    expect(s).toMatchObject({ phase: 'signed-in', access: { role: 'operator' } });
  });

  it('a broker that refuses anonymous asks for a log-in, without blaming anyone', () => {
    const s = run([
      { type: 'start', username: '' },
      { type: 'role', access: { role: 'viewer', source: 'default', name: '' } },
      { type: 'refused', message: 'Not authorized' },
    ]);
    expect(s).toEqual({ phase: 'needs-login', username: '', error: 'This broker needs a log-in.' });
    expect(currentAccess(s)).toBeNull();
  });

  it('refused credentials name the user (as text) and keep the form', () => {
    const s = run([
      { type: 'start', username: '<b>x</b>' },
      { type: 'role', access: viewer },
      { type: 'refused', message: 'Bad username or password' },
    ]);
    expect(s).toEqual({
      phase: 'needs-login',
      username: '<b>x</b>',
      error: 'Log-in refused for "<b>x</b>": Bad username or password.',
    });
  });

  it('the form leads to a new attempt, and a role', () => {
    const s = run([
      { type: 'start', username: '' },
      { type: 'refused', message: 'Not authorized' },
      { type: 'start', username: 'viewer' },
      { type: 'role', access: viewer },
      { type: 'connected' },
    ]);
    expect(s).toMatchObject({ phase: 'signed-in', username: 'viewer' });
    expect(currentAccess(s)).toEqual(viewer);
  });

  it('reconnects keep the session; a later refusal asks again', () => {
    const signedIn = run([
      { type: 'start', username: 'viewer' },
      { type: 'role', access: viewer },
      { type: 'connected' },
    ]);
    expect(loginReducer(signedIn, { type: 'connected' })).toBe(signedIn);
    expect(loginReducer(signedIn, { type: 'refused', message: 'Not authorized' }).phase).toBe(
      'needs-login',
    );
  });

  it('out-of-order events are ignored', () => {
    expect(loginReducer(INITIAL_LOGIN, { type: 'connected' })).toBe(INITIAL_LOGIN);
    const connecting = run([
      { type: 'start', username: '' },
      { type: 'role', access: viewer },
    ]);
    expect(loginReducer(connecting, { type: 'role', access: viewer })).toBe(connecting);
  });

  it('an invalid arm id ends it: nothing connects afterwards', () => {
    const s = run([
      { type: 'invalid', error: 'Invalid arm id' },
      { type: 'start', username: '' },
      { type: 'connected' },
    ]);
    expect(s).toEqual({ phase: 'invalid', error: 'Invalid arm id' });
  });
});
