import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink, UNCHECKED_PERMISSIONS } from '../src/core/link/ArmLink.ts';
import type { LinkPermissions } from '../src/core/link/permissions.ts';
import { FakeMqttClient as FakeClient } from './support/FakeMqttClient.ts';
import { defaultSettings } from '../src/core/config/settings.ts';
import { ControlClaim, type ControlIdentity } from '../src/core/link/ControlClaim.ts';
import { encodeSummary } from '@armtwin/protocol';

const enc = (s: string) => new TextEncoder().encode(s);
/** The arm's summary at `t` naming `holder` (docs/protocol.md § Fleets). */
const summaryOf = (t: number, holder: string | null) =>
  enc(
    encodeSummary({
      t,
      state: 'still',
      why: '',
      health: 'normal',
      alarm: '',
      holder,
      joints: [],
      error: null,
    }),
  );

function setup(who: ControlIdentity, permissions: LinkPermissions = UNCHECKED_PERMISSIONS) {
  const client = new FakeClient();
  const link = new ArmLink(
    new ArmStore(),
    defaultSettings({ protocol: 'http:', host: 'h' }),
    () => client,
  );
  link.start(permissions, {}, who);
  client.emit('connect');
  const holder = (json: object) =>
    client.emit('message', 'arm/arm1/holder', enc(JSON.stringify(json)));
  const summary = (t: number, holder: string | null) =>
    client.emit('message', 'arm/arm1/summary', summaryOf(t, holder));
  const sent = () =>
    client.published
      .filter((p) => !p.payload.startsWith('$PNG'))
      .map(({ topic, payload }) => ({ topic, payload }));
  return { client, link, holder, summary, sent };
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

  // The holder's lease runs from her first beat (a holder that never beats is never timed out):
  // a page whose connection died between its take and its first timed beat kept the arm.
  it('a page that beats sends its first beat right behind its take, so its lease runs at once', () => {
    const beating = { ...UNCHECKED_PERMISSIONS, deadman: true };
    const alice = setup({ name: 'alice', enforced: true, admin: false }, beating);
    alice.holder({ user: null, requests: [] }); // the log-in's take
    const claims = (s: typeof alice) => s.sent().filter((p) => !p.topic.endsWith('/operator'));
    expect(claims(alice)).toEqual([
      { topic: 'arm/arm1/claim/alice', payload: 'take' },
      { topic: 'arm/arm1/claim/alice', payload: 'beat' },
    ]);
    const root = setup({ name: 'root', enforced: true, admin: true }, beating);
    root.holder({ user: 'alice', role: 'operator', since: 1, requests: [] });
    root.link.control.take();
    expect(claims(root)).toEqual([
      { topic: 'arm/arm1/override/root', payload: 'take' },
      { topic: 'arm/arm1/claim/root', payload: 'beat' },
    ]);
    root.link.setMode('model', new ArmStore()); // the copy's claim beats in Model mode
    root.link.control.take();
    expect(claims(root).slice(2)).toEqual([
      { topic: 'arm/arm1-model/claim/root', payload: 'take' },
      { topic: 'arm/arm1-model/claim/root', payload: 'beat' },
    ]);
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

  // docs/cluster.md § The HUD on the cluster: after a node was lost the retained record came
  // through its QoS 1 subscription up to a minute late; the arm's summary (QoS 0) said at once.
  it('until the holder record comes, the arm’s summary says who holds it; never a take by itself', () => {
    const { client, link, holder, summary, sent } = setup({
      name: 'alice',
      enforced: true,
      admin: false,
    });
    expect(client.subscribed).toContain('arm/arm1/summary');
    summary(1000, null);
    expect(link.control.holder?.user).toBeNull();
    expect(sent()).toEqual([]); // the log-in's take waits for the record
    summary(1500, 'bob');
    expect(link.control.heldBy).toBe('bob');
    summary(1200, null); // older than the last one taken: stale
    expect(link.control.heldBy).toBe('bob');
    holder({ user: 'alice', role: 'operator', since: 1, requests: [] });
    summary(2000, 'bob'); // the record has come: summaries say nothing more
    expect(link.control.holding).toBe(true);
  });

  it('after a move to another broker, the summary stands in again until that broker’s record', () => {
    const sent: string[] = [];
    const c = new ControlClaim('arm1', { name: 'alice', enforced: true, admin: false }, (t, p) => {
      sent.push(`${t} ${p}`);
      return true;
    });
    c.onHolder(enc(JSON.stringify({ user: 'alice', requests: [] })));
    c.onSummary(summaryOf(1000, null));
    expect(c.holding).toBe(true); // the record came: the summary says nothing
    c.moved();
    expect(c.holder).toBeNull();
    c.onSummary(summaryOf(5000, null)); // the arm let go of alice while the page moved
    expect(c.holder?.user).toBeNull();
    expect(c.mayMove).toBe(true);
    c.onHolder(enc(JSON.stringify({ user: null, requests: [] })));
    expect(sent).toEqual([]); // never taken again on the page's behalf
  });
});
