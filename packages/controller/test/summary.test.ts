/**
 * The arm's summary (docs/protocol.md § Fleets): what `SummaryTracker` reads of the status
 * payloads and makes of the core, and when `armSummary` publishes it (every 500 ms, at once on
 * an alarm, cleared at stop), on a manual clock and a client that records what it is handed.
 */
import { describe, expect, test } from 'vitest';
import { DEMO_ARM } from '@armtwin/ik';
import {
  encodeControllerError,
  encodeHealth,
  encodePosition,
  encodeTime,
  parseSummary,
  SUMMARY_MIN_GAP_MS,
  SUMMARY_PERIOD_MS,
  type ArmSummary,
  type HolderRecord,
} from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { ControllerCore, jointsFromArm, SummaryTracker } from '../src/index.ts';
import { armSummary } from '../src/mqtt.ts';
import { ArrayDriver } from './array-driver.ts';

function rig() {
  const driver = new ArrayDriver();
  const core = new ControllerCore(jointsFromArm(DEMO_ARM), driver);
  return { driver, core };
}

const healthPayload = (t: number, temps: number[]) =>
  encodeTime(t) + temps.map((c, i) => encodeHealth(i, c, 7400)).join('');

describe('SummaryTracker', () => {
  test('state and pose come from the driver, in servo degrees within the limits', () => {
    const { driver, core } = rig();
    const s = DEMO_ARM.servos[2]!;
    driver.at[2] = core.joints[2]!.pwmOfAngle(45);
    const out = new SummaryTracker().summary(core, null, 1000);
    expect(out.state).toBe('still');
    expect(out.joints).toHaveLength(DEMO_ARM.servos.length);
    expect(out.joints[2]).toEqual({ id: s.id, deg: 45, min: s.minDeg, max: s.maxDeg });
    expect(out.joints[0]!.deg).toBe(0);

    driver.move([{ i: 1, pwm: 1600, ms: 500 }], 1000);
    expect(new SummaryTracker().summary(core, 'alice', 1200)).toMatchObject({
      state: 'moving',
      holder: 'alice',
    });
    driver.notReady = 'gateway: serial line down';
    expect(new SummaryTracker().summary(core, null, 1200)).toMatchObject({
      state: 'not-ready',
      why: 'gateway: serial line down',
    });
  });

  test('health reports give the worst level and its words; a rise in level is an alarm', () => {
    const { core } = rig();
    const tr = new SummaryTracker();
    expect(tr.summary(core, null, 0).health).toBe('unknown');
    expect(tr.note(healthPayload(10, [40, 41, 42]), 10)).toBe(true); // unknown → normal
    expect(tr.note(healthPayload(20, [40, 41, 43]), 20)).toBe(false); // still normal
    expect(tr.note(healthPayload(30, [40, 41, 80]), 30)).toBe(true); // critical
    const s = tr.summary(core, null, 40);
    expect(s.health).toBe('critical');
    expect(s.alarm).toBe('servo 002: 80 °C');
    // A report of one servo keeps the others' last values.
    expect(tr.note(encodeHealth(0, 65, 7400), 50)).toBe(false);
    expect(tr.summary(core, null, 60).alarm).toBe('servo 000: 65 °C; servo 002: 80 °C');
  });

  test('state reports are not parsed; an $ERR is kept and is an alarm', () => {
    const { core } = rig();
    const tr = new SummaryTracker();
    for (let i = 0; i < 100; i++)
      expect(tr.note(encodeTime(i) + encodePosition(0, 1500) + encodePosition(1, 1510), i)).toBe(
        false,
      );
    expect(tr.counters).toEqual({ payloads: 100, parsed: 0 });
    expect(tr.note(encodeTime(200) + encodeControllerError('deadman stop'), 200)).toBe(true);
    expect(tr.summary(core, null, 300).error).toEqual({ t: 200, text: 'deadman stop' });
    expect(tr.counters.parsed).toBe(1);
  });
});

describe('armSummary', () => {
  function published() {
    const sent: { topic: string; payload: string; retain: boolean; at: number }[] = [];
    const clock = new FakeClock(1_000_000);
    const client = {
      connected: true,
      publish(topic: string, payload: string | Buffer, o: { retain?: boolean }) {
        sent.push({ topic, payload: String(payload), retain: o.retain === true, at: clock.now() });
        return client;
      },
      async publishAsync(topic: string, payload: string | Buffer, o: { retain?: boolean }) {
        client.publish(topic, payload, o);
        return undefined;
      },
    };
    const { core } = rig();
    let holder: HolderRecord = { user: null, requests: [] };
    const out = armSummary(client as never, 'arm37', clock);
    out.start(
      () => core,
      () => holder,
    );
    const summaries = () =>
      sent.map((m) => {
        const r = parseSummary(m.payload);
        if (!r.ok) throw new Error(r.error);
        return { ...m, s: r.summary as ArmSummary };
      });
    return { sent, clock, client, out, summaries, setHolder: (h: HolderRecord) => (holder = h) };
  }

  test('retained on arm/{id}/summary every 500 ms while connected, with the holder', () => {
    const r = published();
    r.clock.advance(0);
    r.setHolder({ user: 'bob', requests: [] });
    r.clock.advance(2 * SUMMARY_PERIOD_MS);
    const s = r.summaries();
    expect(s.map((m) => m.at - 1_000_000)).toEqual([0, 500, 1000]);
    expect(s.every((m) => m.topic === 'arm/arm37/summary' && m.retain)).toBe(true);
    expect(s.map((m) => m.s.holder)).toEqual([null, 'bob', 'bob']);
    r.client.connected = false;
    r.clock.advance(2000);
    expect(r.sent).toHaveLength(3);
  });

  test('an overheat goes out at once, never sooner than the gap after the last', async () => {
    const r = published();
    r.clock.advance(0); // the first, at 0
    r.out.note(healthPayload(1, [40, 40, 40])); // unknown → normal: an alarm, due at the gap
    r.clock.advance(SUMMARY_MIN_GAP_MS);
    r.clock.advance(150);
    r.out.note(healthPayload(2, [40, 40, 90])); // critical, 250 ms after the last
    r.clock.advance(0);
    const s = r.summaries();
    expect(s.map((m) => [m.at - 1_000_000, m.s.health])).toEqual([
      [0, 'unknown'],
      [SUMMARY_MIN_GAP_MS, 'normal'],
      [250, 'critical'],
    ]);
    expect(s[2]!.s.alarm).toBe('servo 002: 90 °C');
    expect(r.out.counters.alarms).toBe(2);
    // The period runs on from the last one.
    r.clock.advance(SUMMARY_PERIOD_MS);
    expect(r.sent.at(-1)!.at - 1_000_000).toBe(750);

    await r.out.stop();
    expect(r.sent.at(-1)).toMatchObject({ topic: 'arm/arm37/summary', payload: '', retain: true });
    r.clock.advance(5000);
    expect(r.sent.at(-1)!.payload).toBe('');
  });
});

describe('parseSummary', () => {
  test('bad payloads are refused with the reason', () => {
    expect(parseSummary('nope')).toEqual({ ok: false, error: 'not JSON' });
    expect(parseSummary('[]')).toEqual({ ok: false, error: 'not an object' });
    const good: ArmSummary = {
      t: 1,
      state: 'still',
      why: '',
      health: 'normal',
      alarm: '',
      holder: null,
      joints: [{ id: 0, deg: 1.5, min: -90, max: 90 }],
      error: null,
    };
    expect(parseSummary(JSON.stringify(good))).toEqual({ ok: true, summary: good });
    expect(parseSummary(JSON.stringify({ ...good, state: 'dancing' }))).toEqual({
      ok: false,
      error: 'state: unknown',
    });
    expect(parseSummary(JSON.stringify({ ...good, joints: [{ id: 0 }] })).ok).toBe(false);
    expect(parseSummary('x'.repeat(10_000))).toMatchObject({ ok: false });
  });
});
