/**
 * ArmLink with a role: a viewer's page publishes nothing at all (the embedded broker would
 * close it); an operator's page holds the deadman (will, short keep-alive, retained 1/0); a
 * refused CONNACK reaches the Session, which then asks for a log-in.
 */
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { OPERATOR_BEAT_MS } from '@armtwin/protocol';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import type { ConnectOptions } from '../src/core/link/connectOptions.ts';
import { FakeMqttClient as FakeClient } from './support/FakeMqttClient.ts';
import { defaultSettings, type HudSettings } from '../src/core/config/settings.ts';
import { Session } from '../src/core/auth/Session.ts';
import type { Whoami } from '../src/core/auth/whoami.ts';

function setup(who: Whoami, over: Partial<HudSettings> = {}) {
  const store = new ArmStore();
  const client = new FakeClient();
  let opts: ConnectOptions | undefined;
  const settings = { ...defaultSettings({ protocol: 'http:', host: 'h' }), ...over };
  const link = new ArmLink(store, settings, (_url, o) => {
    opts = o;
    return client;
  });
  const session = new Session({ whoami: () => Promise.resolve(who), queryProblem: null });
  return { store, client, link, session, opts: () => opts };
}

const operator: Whoami = { kind: 'user', name: 'operator', role: 'operator', anonymous: false };
const viewer: Whoami = { kind: 'user', name: 'viewer', role: 'viewer', anonymous: false };

describe('a role on the link', () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it('a viewer publishes nothing: no ping, no jog, no move, no stop, no will', async () => {
    const { client, link, session, opts, store } = setup(viewer, { username: 'viewer' });
    await session.start(link);
    client.emit('connect');
    expect(session.state).toMatchObject({ phase: 'signed-in', access: { role: 'viewer' } });
    expect(opts()?.will).toBeUndefined();
    expect(opts()?.keepalive).toBe(60);
    link.jog(0, 1600);
    link.moveTo(180, 0, 80, undefined, [1500, 1500, 1500, 1500]);
    expect(link.emergencyStop()).toBe(false);
    vi.advanceTimersByTime(5000);
    expect(client.published).toEqual([]);
    expect(store.counters.published).toBe(0);
    link.stop();
    expect(client.published).toEqual([]);
  });

  it('an operator holds the deadman: will 0, keep-alive 2 s, retained 1 at each connect, 0 on release', async () => {
    const { client, link, session, opts } = setup(operator, { username: 'operator' });
    await session.start(link);
    expect(opts()).toMatchObject({
      keepalive: 2,
      will: { topic: 'arm/arm1/operator', payload: '0', qos: 1, retain: true },
    });
    client.emit('connect');
    const presence = () =>
      client.published.filter((p) => p.topic === 'arm/arm1/operator').map((p) => p.payload);
    expect(presence()).toEqual(['1']);
    expect(client.published[0]).toMatchObject({ qos: 1, retain: true });
    client.emit('close');
    client.emit('connect'); // mqtt.js reconnected: hold it again
    expect(presence()).toEqual(['1', '1']);
    link.jog(0, 1600);
    expect(client.published.some((p) => p.payload === '#000P1600T0100!')).toBe(true);
    link.release();
    expect(presence()).toEqual(['1', '1', '0']);
    expect(client.ended).toBe(false); // a clean DISCONNECT after the 0, not a forced close
  });

  it('an operator beats: retained 1 every OPERATOR_BEAT_MS while connected, none while down or after release', async () => {
    const { client, link, session } = setup(operator, { username: 'operator' });
    await session.start(link);
    client.emit('connect');
    const ones = () =>
      client.published.filter((p) => p.topic === 'arm/arm1/operator' && p.payload === '1');
    vi.advanceTimersByTime(10 * OPERATOR_BEAT_MS);
    expect(ones()).toHaveLength(11); // at connect, then ten beats
    expect(ones().every((p) => p.qos === 1 && p.retain)).toBe(true);
    client.emit('close');
    vi.advanceTimersByTime(10 * OPERATOR_BEAT_MS);
    expect(ones()).toHaveLength(11); // nothing queued while offline
    client.emit('connect');
    vi.advanceTimersByTime(OPERATOR_BEAT_MS);
    expect(ones()).toHaveLength(13);
    link.release();
    vi.advanceTimersByTime(10 * OPERATOR_BEAT_MS);
    expect(client.published.filter((p) => p.topic === 'arm/arm1/operator').at(-1)?.payload).toBe(
      '0',
    );
    expect(ones()).toHaveLength(13);
  });

  it('the keep-alive is a setting', async () => {
    const { link, session, opts } = setup(operator, { deadmanKeepAliveS: 5 });
    await session.start(link);
    expect(opts()?.keepalive).toBe(5);
  });

  it('a refused CONNACK stops reconnecting and asks for a log-in', async () => {
    const { client, link, session } = setup({ kind: 'unauthorized' });
    await session.start(link);
    client.emit(
      'error',
      Object.assign(new Error('Connection refused: Not authorized'), { code: 5 }),
    );
    expect(client.ended).toBe(true);
    expect(session.state).toEqual({
      phase: 'needs-login',
      username: '',
      error: 'This broker needs a log-in.',
    });
  });

  it('a locked-out address (whoami 429) is told why and does not connect', async () => {
    const { link, session, opts } = setup(
      { kind: 'locked', retryS: 287 },
      { username: 'operator' },
    );
    await session.start(link);
    expect(opts()).toBeUndefined();
    expect(session.state).toEqual({
      phase: 'needs-login',
      username: 'operator',
      error:
        'Log-in refused for "operator": too many failed log-ins from this address; try again in 287 s.',
    });
  });

  it('a dropped connection is a gap: the Status panel and the charts see it', async () => {
    const { client, link, session, store } = setup(operator);
    await session.start(link);
    client.emit('connect');
    store.history.push(Date.now() / 1000, [40, 40, 40, 40, 40, 40], [7, 7, 7, 7, 7, 7]);
    client.emit('close');
    client.emit('offline');
    expect(link.gap.view(Date.now()).kind).toBe('down');
    expect(store.history.temp[0]!.latest()).toBeNaN();
    expect(store.history.time.length).toBe(2);
    vi.advanceTimersByTime(3000);
    client.emit('connect');
    expect(link.gap.view(Date.now())).toMatchObject({ kind: 'recovered', gapMs: 3000 });
  });

  it('an unknown role (no whoami, no ?role=) watches but may try the stop', async () => {
    const { client, link, session, opts } = setup({ kind: 'unavailable', reason: 'HTTP 404' });
    await session.start(link);
    client.emit('connect');
    expect(opts()?.will).toBeUndefined();
    link.jog(0, 1600);
    vi.advanceTimersByTime(2000);
    expect(client.published).toEqual([]);
    expect(link.emergencyStop()).toBe(true);
    expect(client.published.map((p) => p.payload)).toEqual(['#255PDST!']);
  });

  it('a newer start supersedes an older one still asking whoami', async () => {
    const store = new ArmStore();
    const started: string[] = [];
    const mk = (name: string) =>
      new ArmLink(store, defaultSettings({ protocol: 'http:', host: 'h' }), () => {
        started.push(name);
        return new FakeClient();
      });
    let release: (w: Whoami) => void = () => {};
    let calls = 0;
    const session = new Session({
      whoami: () =>
        ++calls === 1 ? new Promise<Whoami>((r) => (release = r)) : Promise.resolve(operator),
      queryProblem: null,
    });
    const first = session.start(mk('first'));
    await session.start(mk('second'));
    release(viewer);
    await first;
    expect(started).toEqual(['second']);
  });

  it('an invalid arm id in the URL: nothing connects', async () => {
    const { link, opts } = setup(operator);
    const session = new Session({
      whoami: () => Promise.resolve(operator),
      queryProblem: 'Invalid arm id',
    });
    await session.start(link);
    expect(opts()).toBeUndefined();
    expect(session.state.phase).toBe('invalid');
  });
});
