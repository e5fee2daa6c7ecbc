import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink, UNCHECKED_PERMISSIONS } from '../src/core/link/ArmLink.ts';
import { FakeMqttClient as FakeClient } from './support/FakeMqttClient.ts';
import { defaultSettings } from '../src/core/config/settings.ts';
import type { ControlIdentity } from '../src/core/link/ControlClaim.ts';

const enc = (s: string) => new TextEncoder().encode(s);

function setup(who: ControlIdentity) {
  const client = new FakeClient();
  const link = new ArmLink(
    new ArmStore(),
    defaultSettings({ protocol: 'http:', host: 'h' }),
    () => client,
  );
  link.start(UNCHECKED_PERMISSIONS, {}, who);
  client.emit('connect');
  const holder = (json: object) =>
    client.emit('message', 'arm/arm1/holder', enc(JSON.stringify(json)));
  const sent = () =>
    client.published
      .filter((p) => !p.payload.startsWith('$PNG'))
      .map(({ topic, payload }) => ({ topic, payload }));
  return { client, link, holder, sent };
}

describe('ControlClaim in the page (docs/protocol.md § Control)', () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it('logged in: takes control at log-in when nobody holds it, and commands on its own topic', () => {
    const { link, holder, sent } = setup({ name: 'alice', enforced: true, admin: false });
    holder({ user: null, requests: [] });
    expect(sent()).toEqual([{ topic: 'arm/arm1/claim/alice', payload: 'take' }]);
    holder({ user: 'alice', role: 'operator', since: 1, requests: ['bob'] });
    expect(link.mayMove).toBe(true);
    link.emergencyStop();
    expect(sent().at(-1)).toEqual({ topic: 'arm/arm1/control/alice', payload: '#255PDST!' });
    link.control.grant('bob');
    expect(sent().at(-1)).toEqual({ topic: 'arm/arm1/claim/alice', payload: 'grant bob' });
  });

  it('someone else holds the arm: moves are not sent, the stop is, and the page can ask', () => {
    const { link, holder, sent } = setup({ name: 'bob', enforced: true, admin: false });
    holder({ user: 'alice', role: 'operator', since: 1, requests: [] });
    expect(link.mayMove).toBe(false);
    expect(link.control.heldBy).toBe('alice');
    expect(link.sendGroup('{#000P1500T500!}')).toBe(false);
    expect(link.emergencyStop()).toBe(true);
    link.control.ask();
    expect(sent().map((p) => p.payload)).toEqual(['#255PDST!', 'ask']);
  });

  it('anonymous demo: the plain topic until the page takes control under its own name', () => {
    const { link, holder, sent } = setup({ name: 'guest-1a2b', enforced: false, admin: false });
    holder({ user: null, requests: [] });
    expect(sent()).toEqual([]); // nothing is taken by itself in the demo
    link.sendGroup('{#000P1500T500!}');
    expect(sent().at(-1)?.topic).toBe('arm/arm1/control');
    holder({ user: 'guest-1a2b', role: 'operator', since: 1, requests: [] });
    link.sendGroup('{#000P1500T500!}');
    expect(sent().at(-1)?.topic).toBe('arm/arm1/control/guest-1a2b');
  });

  it('an administrator takes a held arm on its override topic', () => {
    const { link, holder, sent } = setup({ name: 'root', enforced: true, admin: true });
    holder({ user: 'alice', role: 'operator', since: 1, requests: [] });
    link.control.take();
    expect(sent().at(-1)).toEqual({ topic: 'arm/arm1/override/root', payload: 'take' });
  });
});
