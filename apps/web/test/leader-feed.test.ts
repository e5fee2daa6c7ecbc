/**
 * The page's leader feed (src/core/leader/LeaderFeed.ts): a leader gateway's pose becomes the
 * ghost's pose in the store's slots (the SO-101's ids 1–6 → slots 0–5), only while fresh, the
 * newest leader first; its retained state says whether it drives the arm; bad messages are
 * counted by kind and change nothing; another arm's leaders are not this arm's.
 */
import { describe, expect, test } from 'vitest';
import { LeaderFeed, LEADER_POSE_FRESH_MS } from '../src/core/leader/LeaderFeed.ts';
import type { LinkTap } from '../src/core/link/LinkInbox.ts';

const SERVOS = [1, 2, 3, 4, 5, 6].map((id) => ({ id, polarity: 1 }));

function feed(arm = 'so101') {
  let t = 1000;
  const taps: LinkTap[] = [];
  const f = new LeaderFeed(
    () => SERVOS,
    () => t,
  );
  f.attach({ settings: { armId: arm }, tap: (tap) => taps.push(tap) });
  const send = (topic: string, payload: string) => {
    for (const tap of taps) if (tap.matches(topic)) tap.onMessage(topic, Buffer.from(payload));
  };
  return { f, taps, send, at: (ms: number) => (t = ms) };
}

const ghost = (f: LeaderFeed, now: number) => {
  const out = new Float64Array(6);
  return f.sample(now, out) ? Array.from(out) : null;
};

describe('LeaderFeed', () => {
  test("subscribes to the arm's leader poses and states, not their enables", () => {
    const { taps } = feed();
    expect(taps.map((t) => t.filter)).toEqual(['arm/so101/leader/+', 'arm/so101/leader/+/state']);
    expect(taps.some((t) => t.matches('arm/so101/leader/alice/enable'))).toBe(false);
    expect(taps.some((t) => t.matches('arm/other/leader/alice'))).toBe(false);
  });

  test("a leader's pose is the ghost's, servo by id into the store's slots, while fresh", () => {
    const { f, send } = feed();
    expect(ghost(f, 1000)).toBeNull();
    send('arm/so101/leader/alice', '$TIM:1700000000000!{#001A-020.04!#002A+010.00!#006A+040.00!}');
    expect(ghost(f, 1100)).toEqual([-20.04, 10, NaN, NaN, NaN, 40]);
    expect(f.onGhost).toBe('alice');
    expect(ghost(f, 1000 + LEADER_POSE_FRESH_MS + 1)).toBeNull();
    expect(f.onGhost).toBe('');
  });

  test('the newest of two leaders is shown', () => {
    const { f, send, at } = feed();
    send('arm/so101/leader/alice', '{#001A+010.00!}');
    at(1500);
    send('arm/so101/leader/bob', '{#001A-030.00!}');
    expect(ghost(f, 1600)?.[0]).toBe(-30);
    expect(f.onGhost).toBe('bob');
  });

  test('the retained state says whether it drives the arm, and why not', () => {
    const { f, send } = feed();
    send('arm/so101/leader/alice/state', '{"following":true,"reason":""}');
    expect(f.list).toEqual([
      { user: 'alice', state: { following: true, reason: '' }, poseAt: NaN },
    ]);
    const v = f.version;
    send('arm/so101/leader/alice/state', '{"following":false,"reason":"emergency stop by bob"}');
    expect(f.version).toBeGreaterThan(v);
    expect(f.list[0]!.state).toEqual({ following: false, reason: 'emergency stop by bob' });
  });

  test('bad messages are counted by kind and change nothing', () => {
    const { f, send } = feed();
    send('arm/so101/leader/alice/state', '{"following":"yes"}');
    send('arm/so101/leader/alice/state', 'not json');
    send('arm/so101/leader/alice', '{#001A-020.00!junk}');
    send('arm/so101/leader/alice', '{#009A+001.00!}');
    expect(f.rejected).toEqual({ state: 2, pose: 1, servo: 1 });
    expect(f.list[0]!.state).toBeNull();
  });

  test("another arm's leader is forgotten when the page follows another arm", () => {
    const { f, send } = feed();
    send('arm/so101/leader/alice', '{#001A+010.00!}');
    f.attach({ settings: { armId: 'arm1' }, tap: () => {} });
    expect(f.list).toEqual([]);
    send('arm/so101/leader/alice', '{#001A+010.00!}'); // the old link's tap: ignored
    expect(ghost(f, 1100)).toBeNull();
  });
});
