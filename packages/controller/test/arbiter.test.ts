import { describe, expect, it } from 'vitest';
import {
  parseClaim,
  parseHolder,
  parseUserTopic,
  type AuditEvent,
  type HolderRecord,
} from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { ControlArbiter } from '../src/index.ts';

function arbiter() {
  const clock = new FakeClock();
  const sent: string[] = [];
  const errors: string[] = [];
  const holders: HolderRecord[] = [];
  const audit: AuditEvent[] = [];
  const a = new ControlArbiter('arm1', {
    now: () => clock.now(),
    setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
    clearTimeout: (h) => clock.clearTimeout(h),
    forward: (p) => sent.push(typeof p === 'string' ? p : Buffer.from(p).toString()),
    refuse: (m) => errors.push(m),
    holder: (r) => holders.push(r),
    audit: (e) => audit.push(e),
  });
  const say = (user: string, words: string) => a.fromMessage(`arm/arm1/claim/${user}`, words);
  const move = (user: string, frame = '#000P1500T1000!') =>
    a.fromMessage(user ? `arm/arm1/control/${user}` : 'arm/arm1/control', frame);
  return { a, clock, sent, errors, holders, audit, say, move };
}

describe('ControlArbiter', () => {
  it('lets every payload through while nobody holds the arm (the demo, mosquitto_pub)', () => {
    const t = arbiter();
    t.move('');
    t.move('bob');
    expect(t.sent).toEqual(['#000P1500T1000!', '#000P1500T1000!']);
    expect(t.a.holder.user).toBeNull();
  });

  it("refuses a non-holder's moves with $ERR and an audit event, but passes its stops", () => {
    const t = arbiter();
    t.say('alice', 'take');
    expect(t.holders.at(-1)).toMatchObject({ user: 'alice', role: 'operator', requests: [] });
    t.move('alice');
    t.move('bob');
    t.move('');
    t.move('bob', '{#000P1000T500!#001P1000T500!}');
    t.move('bob', '#000P1000T500!#255PDST!');
    t.move('bob', '$PNG:7!');
    expect(t.sent).toEqual(['#000P1500T1000!', '#255PDST!', '$PNG:7!']);
    expect(t.errors[0]).toBe('controlled by alice');
    expect(t.audit.filter((e) => e.kind === 'refused-command').map((e) => e.by)).toEqual([
      'bob',
      '',
    ]);
    expect(t.a.counters.refusedCommands).toBe(4);
  });

  it('hands over on grant, refuses forged grants, and stops the arm at each change', () => {
    const t = arbiter();
    t.say('alice', 'take');
    t.say('bob', 'take');
    expect(t.audit.at(-1)).toMatchObject({ by: 'bob', kind: 'refused-claim' });
    t.say('bob', 'ask');
    expect(t.holders.at(-1)?.requests).toEqual(['bob']);
    t.say('bob', 'grant bob'); // forged: only the holder may grant
    expect(t.audit.at(-1)).toMatchObject({
      kind: 'refused-claim',
      detail: 'only alice may grant control',
    });
    t.say('alice', 'grant carol');
    expect(t.audit.at(-1)?.detail).toBe('carol has not asked for control');
    t.sent.length = 0;
    t.say('alice', 'grant bob');
    expect(t.sent).toEqual(['#255PDST!']);
    expect(t.holders.at(-1)).toMatchObject({ user: 'bob', requests: [] });
    t.move('alice');
    t.move('bob');
    expect(t.sent).toEqual(['#255PDST!', '#000P1500T1000!']);
  });

  it('refuse keeps the holder; release frees the arm', () => {
    const t = arbiter();
    t.say('alice', 'take');
    t.say('bob', 'ask');
    t.say('alice', 'refuse bob');
    expect(t.holders.at(-1)).toMatchObject({ user: 'alice', requests: [] });
    expect(t.audit.at(-1)?.kind).toBe('refused');
    t.say('alice', 'release');
    expect(t.holders.at(-1)?.user).toBeNull();
    expect(t.sent).toEqual(['#255PDST!']);
  });

  it('a beating holder that goes quiet loses the arm, which stops', () => {
    const t = arbiter();
    t.say('alice', 'take');
    t.say('alice', 'beat');
    t.clock.advance(2000);
    t.say('alice', 'beat');
    t.clock.advance(2000);
    expect(t.a.holder.user).toBe('alice');
    t.clock.advance(1000);
    expect(t.a.holder.user).toBeNull();
    expect(t.audit.at(-1)?.kind).toBe('lost');
    expect(t.sent).toEqual(['#255PDST!']);
    t.say('bob', 'take');
    expect(t.a.holder.user).toBe('bob');
  });

  it('an administrator takes over outright', () => {
    const t = arbiter();
    t.say('alice', 'take');
    t.a.fromMessage('arm/arm1/override/root', 'take');
    expect(t.holders.at(-1)).toMatchObject({ user: 'root', role: 'admin' });
    expect(t.audit.at(-1)).toMatchObject({ kind: 'admin-take-over', by: 'root' });
    expect(t.sent).toEqual(['#255PDST!']);
  });

  it('parses claims, holders and user topics, refusing nonsense', () => {
    expect(parseClaim(' grant bob\n')).toEqual({ op: 'grant', to: 'bob' });
    expect(parseClaim('grant')).toHaveProperty('error');
    expect(parseClaim('take over')).toHaveProperty('error');
    expect(parseClaim('grant a/b')).toHaveProperty('error');
    expect(parseUserTopic('arm/arm1/control/alice')).toEqual({
      armId: 'arm1',
      kind: 'control',
      user: 'alice',
    });
    expect(parseUserTopic('arm/arm1/status/alice')).toBeNull();
    expect(parseHolder('{"user":"a b"}')).toBeNull();
    expect(parseHolder('')).toEqual({ user: null, requests: [] });
  });
});

describe('ControlArbiter: the record of stops', () => {
  it('records every emergency stop with its sender, and who set the arm going again', () => {
    const t = arbiter();
    t.move('', '#255PDST!');
    t.move('alice', '#000PDST!'); // one servo's stop is not an emergency stop
    t.move('bob', '$PNG:1!'); // nothing that moves: the stop still stands
    t.move('bob', '#000P1500T500!');
    t.move('bob', '#000P1600T500!'); // only the first move after the stop
    t.say('alice', 'take');
    t.move('bob', '#255PDST!'); // a non-holder's stop still stops the arm, and is recorded
    expect(t.sent.at(-1)).toBe('#255PDST!');
    t.move('bob', '#000P1500T500!'); // refused: not the first move after the stop
    t.move('alice', '#000P1500T500!');
    expect(
      t.audit
        .filter((e) => e.kind.startsWith('e-stop'))
        .map((e) => `${e.kind} ${e.by || '(plain)'}: ${e.detail}`),
    ).toEqual([
      'e-stop (plain): a client on a plain topic pressed the emergency stop',
      'e-stop-released bob: bob moved the arm again after the emergency stop',
      'e-stop bob: bob pressed the emergency stop',
      'e-stop-released alice: alice moved the arm again after the emergency stop',
    ]);
  });

  it('names the sender of the payload the arm is taking in, for refusals the arm makes itself', () => {
    const seen: string[] = [];
    const clock = new FakeClock();
    const a: ControlArbiter = new ControlArbiter('arm1', {
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (h) => clock.clearTimeout(h),
      forward: () => seen.push(a.author),
      refuse: () => {},
      holder: () => {},
      audit: () => {},
    });
    a.fromMessage('arm/arm1/control/carol', '#000P1500T500!');
    a.fromMessage('arm/arm1/control', '#000P1500T500!');
    expect(seen).toEqual(['carol', '']);
    expect(a.author).toBe('');
  });
});
