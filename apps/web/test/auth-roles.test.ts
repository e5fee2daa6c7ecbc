import { describe, expect, it } from 'vitest';
import {
  permissionsFor,
  STOP_NEEDS_OPERATOR,
  VIEWER_REASON,
  type Access,
} from '../src/core/auth/roles.ts';
import { basicAuth, parseWhoami, resolveAccess, type Whoami } from '../src/core/auth/whoami.ts';
import { armQueryProblem } from '../src/core/config/queryProblems.ts';
import { applyQuery, defaultSettings } from '../src/core/config/settings.ts';

const access = (role: Access['role'], source: Access['source']): Access => ({
  role,
  source,
  name: 'x',
});

describe('permissionsFor (role → what the page offers)', () => {
  const cases: [string, Access, { command: boolean; stop: boolean; deadman: boolean }][] = [
    [
      'operator (server)',
      access('operator', 'server'),
      { command: true, stop: true, deadman: true },
    ],
    ['operator (demo)', access('operator', 'demo'), { command: true, stop: true, deadman: true }],
    ['operator (?role=)', access('operator', 'hint'), { command: true, stop: true, deadman: true }],
    [
      'viewer (server)',
      access('viewer', 'server'),
      { command: false, stop: false, deadman: false },
    ],
    ['viewer (?role=)', access('viewer', 'hint'), { command: false, stop: false, deadman: false }],
    [
      'unknown → viewer',
      access('viewer', 'default'),
      { command: false, stop: true, deadman: false },
    ],
    ['device', access('device', 'server'), { command: false, stop: false, deadman: false }],
    ['middleware', access('middleware', 'server'), { command: false, stop: false, deadman: false }],
  ];
  it.each(cases)('%s', (_name, a, expected) => {
    expect(permissionsFor(a)).toMatchObject(expected);
  });

  it('a viewer is told why, and that the stop needs an operator account', () => {
    const p = permissionsFor(access('viewer', 'server'));
    expect(p.reason).toBe(VIEWER_REASON);
    expect(p.stopRefusal).toBe(STOP_NEEDS_OPERATOR);
  });

  it('an unknown role may stop (best effort, flagged) but not move', () => {
    const p = permissionsFor(access('viewer', 'default'));
    expect(p.stopUnconfirmed).toBe(true);
    expect(p.reason).toContain('?role=operator');
  });

  it('an operator has no reason to show', () => {
    expect(permissionsFor(access('operator', 'server')).reason).toBe('');
  });
});

describe('whoami', () => {
  it('parses the answers of armtwin up', () => {
    expect(parseWhoami(200, { name: 'viewer', role: 'viewer' })).toEqual({
      kind: 'user',
      name: 'viewer',
      role: 'viewer',
      anonymous: false,
    });
    expect(parseWhoami(200, { name: '', role: 'operator', anonymous: true })).toMatchObject({
      role: 'operator',
      anonymous: true,
    });
    expect(parseWhoami(200, { name: 'arm1', role: 'device', arm: 'arm1' })).toMatchObject({
      role: 'device',
    });
    expect(parseWhoami(401, null)).toEqual({ kind: 'unauthorized' });
    expect(parseWhoami(429, null, '287')).toEqual({ kind: 'locked', retryS: 287 });
    expect(parseWhoami(429, null, null)).toEqual({ kind: 'locked', retryS: 60 });
    expect(parseWhoami(404, null)).toEqual({ kind: 'unavailable', reason: 'HTTP 404' });
    expect(parseWhoami(200, { name: 'x', role: 'root' }).kind).toBe('unavailable');
    expect(parseWhoami(200, '<html>').kind).toBe('unavailable');
  });

  it('resolves the role: the server wins, then ?role=, then viewer', () => {
    const user: Whoami = { kind: 'user', name: 'viewer', role: 'viewer', anonymous: false };
    const demo: Whoami = { kind: 'user', name: '', role: 'operator', anonymous: true };
    const none: Whoami = { kind: 'unavailable', reason: 'HTTP 404' };
    expect(resolveAccess(user, 'operator', 'viewer')).toEqual({
      role: 'viewer',
      source: 'server',
      name: 'viewer',
    });
    expect(resolveAccess(demo, '', '')).toMatchObject({ role: 'operator', source: 'demo' });
    expect(resolveAccess(none, 'operator', 'op')).toEqual({
      role: 'operator',
      source: 'hint',
      name: 'op',
    });
    expect(resolveAccess(none, '', 'op')).toMatchObject({ role: 'viewer', source: 'default' });
    expect(resolveAccess({ kind: 'unauthorized' }, '', '')).toMatchObject({
      role: 'viewer',
      source: 'default',
    });
  });

  it('encodes HTTP Basic as UTF-8', () => {
    expect(basicAuth('viewer', 'viewer-demo')).toBe(
      `Basic ${Buffer.from('viewer:viewer-demo').toString('base64')}`,
    );
    expect(basicAuth('zoë', 'π')).toBe(`Basic ${Buffer.from('zoë:π', 'utf8').toString('base64')}`);
  });
});

describe('query', () => {
  const base = defaultSettings({ protocol: 'http:', host: 'h' });
  it('reads role= and keepalive=', () => {
    expect(applyQuery(base, '?role=operator&keepalive=5')).toMatchObject({
      roleHint: 'operator',
      deadmanKeepAliveS: 5,
    });
    expect(applyQuery(base, '?role=admin')).toMatchObject({ roleHint: '', deadmanKeepAliveS: 2 });
  });

  it('an invalid arm id is an error, not a topic', () => {
    expect(armQueryProblem('?arm=arm-2')).toBeNull();
    expect(armQueryProblem('')).toBeNull();
    for (const bad of ['<img src=x>', 'ARM1', 'a/b', '+', '#', '', 'a'.repeat(33)]) {
      expect(armQueryProblem(`?arm=${encodeURIComponent(bad)}`)).toContain('Invalid arm id');
      expect(applyQuery(base, `?arm=${encodeURIComponent(bad)}`).armId).toBe('arm1');
    }
  });
});
