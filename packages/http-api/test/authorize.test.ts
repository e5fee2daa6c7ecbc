/**
 * The API's one log-in step and its rules (SECURITY.md): who a request's `Authorization` header
 * says the caller is, and what that caller may do, for `armtwin up` (anonymous = the local demo)
 * and the middleware (anonymous changes from loopback only).
 */
import type http from 'node:http';
import { describe, expect, test } from 'vitest';
import { hashPassword, LoginThrottle, parseUsers } from '@armtwin/auth';
import { createAuthorize, refusal, type AuthOptions, type Right } from '../src/authorize.ts';

const users = parseUsers(
  JSON.stringify({
    users: ['operator', 'viewer', 'admin'].map((name) => ({
      name,
      role: name,
      password: hashPassword(`pw-${name}`, { iterations: 10 }),
    })),
  }),
);
const basic = (u: string, p = `pw-${u}`) => `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
const request = (authorization?: string, from = '127.0.0.1') =>
  ({
    headers: authorization ? { authorization } : {},
    socket: { remoteAddress: from },
  }) as unknown as http.IncomingMessage;

/** The status the rules answer (200 when the caller may). */
async function status(o: AuthOptions, right: Right, authorization?: string, from?: string) {
  const req = request(authorization, from);
  return refusal(o, req, await createAuthorize(o)(req), right)?.status ?? 200;
}

describe('armtwin up: the local demo without a users file', () => {
  const demo: AuthOptions = { logins: null, apiToken: '', anonymous: 'anywhere' };
  test('anyone reads and changes, whatever header the page sends', async () => {
    for (const right of ['data', 'view', 'change'] as const) {
      expect(await status(demo, right)).toBe(200);
      expect(await status(demo, right, basic('anyone'), '10.0.0.5')).toBe(200);
    }
  });
});

describe('the middleware without a users file', () => {
  const open: AuthOptions = { logins: null, apiToken: '', anonymous: 'loopback' };
  test('reads are open; robots are changed from this machine only', async () => {
    expect(await status(open, 'data', undefined, '10.0.0.5')).toBe(200);
    expect(await status(open, 'change', undefined, '127.0.0.1')).toBe(200);
    expect(await status(open, 'change', undefined, '::ffff:127.0.0.1')).toBe(200);
    expect(await status(open, 'change', undefined, '::1')).toBe(200);
    expect(await status(open, 'change', undefined, '10.0.0.5')).toBe(403);
  });

  test('with API_TOKEN: reads need it; it never changes a robot', async () => {
    const token: AuthOptions = { ...open, apiToken: 's3cret' };
    expect(await status(token, 'data')).toBe(401);
    expect(await status(token, 'data', 'Bearer nope')).toBe(401);
    expect(await status(token, 'data', 'Bearer s3cret')).toBe(200);
    expect(await status(token, 'view', 'Bearer s3cret', '10.0.0.5')).toBe(200);
    expect(await status(token, 'change', 'Bearer s3cret')).toBe(403);
  });
});

describe('with a users file', () => {
  const withUsers = (): AuthOptions => ({
    logins: new LoginThrottle(users, { perUser: 2, perAddress: 10, windowS: 60, lockoutS: 300 }),
    apiToken: 's3cret',
    anonymous: 'anywhere',
  });

  test('any user reads; only operators and admins change; nobody anonymous', async () => {
    const o = withUsers();
    expect(await status(o, 'data', basic('viewer'))).toBe(200);
    expect(await status(o, 'view', basic('viewer'))).toBe(200);
    expect(await status(o, 'change', basic('viewer'))).toBe(403);
    expect(await status(o, 'change', basic('operator'))).toBe(200);
    expect(await status(o, 'change', basic('admin'))).toBe(200);
    for (const right of ['data', 'view', 'change'] as const)
      expect(await status(o, right)).toBe(401);
    expect(await status(o, 'change', basic('operator', 'wrong'))).toBe(401);
  });

  test('a locked-out address is told so (429) on every route, even with the right password', async () => {
    const o = withUsers();
    for (let i = 0; i < 3; i++) await status(o, 'change', basic('operator', 'guess'));
    const req = request(basic('operator'));
    const why = refusal(o, req, await createAuthorize(o)(req), 'data');
    expect(why).toMatchObject({
      status: 429,
      error: expect.stringMatching(/too many failed log-ins/),
    });
    expect(why!.retryAfterS).toBeGreaterThan(290);
    expect(await status(o, 'change', basic('operator'))).toBe(429);
  });
});
