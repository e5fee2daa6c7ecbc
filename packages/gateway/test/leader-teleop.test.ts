/**
 * The leader arm's pure core: leader poses in, the follower's targets out as its user's angle
 * moves, only while it holds the follower and follows; an e-stop, a lost lease or a refused take
 * end following until `1` on the enable topic; refusals counted by kind; the pose announced.
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { LeaderTeleop } from '../src/leader-teleop.ts';
import { BUS_MODELS_DIR } from '../src/start-bus-gateway.ts';

const NAMES = [
  'shoulder_pan',
  'shoulder_lift',
  'elbow_flex',
  'wrist_flex',
  'wrist_roll',
  'gripper',
];
/** The shipped SO-101's announcement with ids 11–16 (so the mapping by name shows). */
const so101 = JSON.parse(
  fs.readFileSync(path.join(BUS_MODELS_DIR, 'so101', 'profile.json'), 'utf8'),
) as { servos: { id: string; name: string }[]; poses: { home: { servos: object } } };
so101.servos.forEach((s, i) => (s.id = String(11 + i).padStart(3, '0')));
so101.poses.home.servos = Object.fromEntries(so101.servos.map((s) => [s.id, 0]));
const ANNOUNCEMENT = JSON.stringify({ name: 'so101', title: 'SO-101', profile: so101 });

function rig() {
  const out: { topic: string; payload: string; retain: boolean }[] = [];
  const first: string[] = [];
  const t = new LeaderTeleop(
    { follower: 'so101', user: 'alice', servos: NAMES.map((name, i) => ({ id: i + 1, name })) },
    {
      publish: (topic, payload, o) => out.push({ topic, payload, retain: o.retain }),
      now: () => 1_700_000_000_000,
      onFirst: (kind) => first.push(kind),
    },
  );
  const on = (topic: string) => out.filter((m) => m.topic === topic).map((m) => m.payload);
  const pose = (...deg: number[]) => t.leaderPose(deg.map((d, i) => ({ id: i + 1, degrees: d })));
  const audit = (kind: string, by: string, detail = '') =>
    t.audit(JSON.stringify({ at: 1, by, kind, detail }));
  return { t, out, first, on, pose, audit };
}

describe('LeaderTeleop', () => {
  test('takes the follower, then sends each moved pose as one group of the follower ids', () => {
    const r = rig();
    r.t.connected();
    expect(r.on('arm/so101/claim/alice')).toEqual(['take']);
    r.t.followerProfile(ANNOUNCEMENT);
    r.pose(10, 0, 0, 0, 0, 50); // not holding yet: announced only
    expect(r.on('arm/so101/control/alice')).toEqual([]);
    expect(r.on('arm/so101/leader/alice')).toEqual([
      '$TIM:1700000000000!{#001A+010.00!#002A+000.00!#003A+000.00!#004A+000.00!#005A+000.00!#006A+050.00!}',
    ]);
    r.t.holderRecord(JSON.stringify({ user: 'alice', requests: [] }));
    r.pose(10, 0, 0, 0, 0, 50);
    r.pose(10.05, 0, 0, 0, 0, 50); // within the dead band: not sent again
    r.pose(-12.5, 0, 0, 0, 0, 50);
    expect(r.on('arm/so101/control/alice')).toEqual([
      '{#011A+010.00T0000!#012A+000.00T0000!#013A+000.00T0000!#014A+000.00T0000!#015A+000.00T0000!#016A+050.00T0000!}',
      '{#011A-012.50T0000!#012A+000.00T0000!#013A+000.00T0000!#014A+000.00T0000!#015A+000.00T0000!#016A+050.00T0000!}',
    ]);
    r.t.beat();
    expect(r.on('arm/so101/claim/alice')).toEqual(['take', 'beat']);
  });

  test('an e-stop ends following (poses still announced) until 1 on the enable topic', () => {
    const r = rig();
    r.t.connected();
    r.t.followerProfile(ANNOUNCEMENT);
    r.t.holderRecord(JSON.stringify({ user: 'alice', requests: [] }));
    r.audit('e-stop', 'bob', 'bob pressed the emergency stop');
    expect(r.t.state).toEqual({
      following: false,
      reason:
        'bob pressed the emergency stop; publish 1 on arm/so101/leader/alice/enable to follow again',
    });
    expect(JSON.parse(r.on('arm/so101/leader/alice/state').at(-1)!)).toMatchObject({
      following: false,
    });
    r.pose(20, 0, 0, 0, 0, 0);
    expect(r.on('arm/so101/control/alice')).toEqual([]);
    expect(r.on('arm/so101/leader/alice')).toHaveLength(1);
    r.t.enable('0');
    expect(r.t.counters.rejected).toEqual({ enable: 1 });
    r.t.enable('1');
    expect(r.t.state.following).toBe(true);
    r.pose(20, 0, 0, 0, 0, 0);
    expect(r.on('arm/so101/control/alice')).toHaveLength(1);
  });

  test("a lost lease or a refused take ends following; the follower's refusals are counted by kind", () => {
    const r = rig();
    r.t.connected();
    r.t.followerProfile(ANNOUNCEMENT);
    r.t.holderRecord(JSON.stringify({ user: 'alice', requests: [] }));
    r.audit('refused-keep-out', 'alice', 'into zone bin');
    r.audit('refused-keep-out', 'carol', 'not ours');
    expect(r.t.counters.refused).toEqual({ 'refused-keep-out': 1 });
    expect(r.t.state.following).toBe(true);
    r.t.holderRecord(JSON.stringify({ user: 'bob', requests: [] }));
    expect(r.t.state.reason).toMatch(/^control passed to bob; publish 1/);
    r.t.enable('1');
    expect(r.on('arm/so101/claim/alice')).toEqual(['take', 'take']);
    r.audit('refused-claim', 'alice', 'controlled by bob');
    expect(r.t.state.reason).toMatch(/controlled by bob: ask for control/);
  });

  test('a follower without one of the leader servos is not driven; bad input is counted', () => {
    const r = rig();
    const other = JSON.parse(ANNOUNCEMENT) as { profile: typeof so101 };
    other.profile.servos[5]!.name = 'jaw';
    r.t.followerProfile(JSON.stringify(other));
    expect(r.t.state).toMatchObject({ following: false });
    expect(r.t.state.reason).toMatch(/no servo named gripper/);
    r.t.followerProfile('{');
    r.t.audit('nope');
    r.t.holderRecord('[1]');
    expect(r.t.counters.rejected).toEqual({ profile: 1, audit: 1, holder: 1 });
  });
});
