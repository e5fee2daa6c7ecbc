import { describe, expect, it } from 'vitest';
import { hashPassword, LoginThrottle, parseUsers } from '@armtwin/auth';
import { authorize, mayWatch, requestCredentials } from '../src/access.ts';

const b64 = (s: string) => Buffer.from(s).toString('base64');

describe('who may watch a camera', () => {
  it('viewers and operators any arm, a device its own, the middleware (recording) any arm', () => {
    expect(mayWatch({ name: 'v', role: 'viewer' }, 'arm1')).toBe(true);
    expect(mayWatch({ name: 'o', role: 'operator' }, 'arm2')).toBe(true);
    expect(mayWatch({ name: 'arm1', role: 'device', arm: 'arm1' }, 'arm1')).toBe(true);
    expect(mayWatch({ name: 'arm1', role: 'device', arm: 'arm1' }, 'arm2')).toBe(false);
    expect(mayWatch({ name: 'arm1', role: 'device', arm: 'arm1' }, null)).toBe(false);
    expect(mayWatch({ name: 'mw', role: 'middleware' }, 'arm1')).toBe(true);
  });

  it('takes credentials from the header first, else from the query', () => {
    expect(requestCredentials(`Basic ${b64('ann:pw')}`, '/x?access_token=t')).toEqual({
      type: 'basic',
      name: 'ann',
      password: 'pw',
    });
    expect(requestCredentials('Bearer abc', undefined)).toEqual({ type: 'bearer', token: 'abc' });
    expect(requestCredentials(undefined, '/camera/front.h264?access_token=t%2B1')).toEqual({
      type: 'bearer',
      token: 't+1',
    });
    expect(
      requestCredentials(
        undefined,
        `/camera/front.h264?auth=${encodeURIComponent(b64('ann:p:w'))}`,
      ),
    ).toEqual({
      type: 'basic',
      name: 'ann',
      password: 'p:w',
    });
    expect(requestCredentials(undefined, '/camera/front.mjpeg')).toBeNull();
  });

  it('decides with the users file and the token', async () => {
    const users = parseUsers(
      JSON.stringify({
        users: [
          { name: 'vera', role: 'viewer', password: hashPassword('v-pass') },
          { name: 'arm2', role: 'device', arm: 'arm2', password: hashPassword('d-pass') },
        ],
      }),
    );
    const access = { logins: new LoginThrottle(users), token: 'tok' };
    const req = (authorization?: string, url?: string) => ({
      authorization,
      url,
      address: '10.0.0.1',
    });
    expect(await authorize({ logins: null, token: '' }, req(), 'arm1')).toEqual({
      ok: true,
      who: 'anonymous',
    });
    expect(await authorize(access, req(), 'arm1')).toMatchObject({ ok: false, status: 401 });
    expect(await authorize(access, req(`Basic ${b64('vera:v-pass')}`), 'arm1')).toEqual({
      ok: true,
      who: 'vera',
    });
    expect(await authorize(access, req(`Basic ${b64('vera:wrong')}`), 'arm1')).toMatchObject({
      ok: false,
      status: 401,
    });
    expect(await authorize(access, req(`Basic ${b64('arm2:d-pass')}`), 'arm1')).toMatchObject({
      ok: false,
      status: 403,
    });
    expect(
      await authorize(access, req(undefined, `/x?auth=${b64('arm2:d-pass')}`), 'arm2'),
    ).toEqual({ ok: true, who: 'arm2' });
    expect(await authorize(access, req('Bearer tok'), 'arm1')).toEqual({ ok: true, who: 'token' });
    expect(await authorize(access, req('Bearer nope'), 'arm1')).toMatchObject({
      ok: false,
      status: 401,
    });
    // `armtwin up`'s in-process middleware, with the token minted for this run
    const withRecorder = { ...access, recorderToken: 'rec-123' };
    expect(await authorize(withRecorder, req('Bearer rec-123'), 'arm2')).toEqual({
      ok: true,
      who: 'recorder',
    });
    expect(await authorize(access, req('Bearer rec-123'), 'arm2')).toMatchObject({ status: 401 });
  });
});
