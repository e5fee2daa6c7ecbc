import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { jointFromPwm, parseUrdfJoints } from '@armtwin/robot';
import { ArmFeed } from '../src/arm-feed.ts';
import { plannedPose } from '../src/plan-feed.ts';

const { profile } = readRobotFolder('armtwin5');
const urdf = parseUrdfJoints(
  fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', profile.urdf), 'utf8'),
);
if (!urdf.ok) throw new Error(urdf.errors.join('; '));
const bytes = (v: unknown) => new TextEncoder().encode(JSON.stringify(v));
const END = { '000': 1500, '001': 1700, '002': 1300, '003': 1500, '004': 1500, '005': 1200 };
const planned = {
  id: 'p1',
  status: 'planned',
  code: 0,
  message: 'joint plan',
  mode: 'joint',
  durationMs: 1840,
  samples: 93,
  end: END,
  t: 1_700_000_000_500,
};

describe('plannedPose: a plan as the arm tells it on arm/{id}/feedback', () => {
  test("the end pose in the profile's joints; a servo the plan leaves out stays where reported", () => {
    const { '005': _gripper, ...partial } = END;
    const p = plannedPose(
      profile,
      bytes({ ...planned, end: partial }),
      new Map([['gripper', 0.01]]),
    );
    if (!p || p === 'unreadable') throw new Error('no plan');
    expect(p).toMatchObject({ id: 'p1', status: 'planned', mode: 'joint', durationMs: 1840 });
    expect(p.joints.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    expect(p.joints[1]!.position).toBe(jointFromPwm(profile.servos[1]!, 1700));
    expect(p.joints[5]!.position).toBe(0.01);
  });

  test('a re-plan during execution counts; other states do not; junk is unreadable', () => {
    const re = plannedPose(
      profile,
      bytes({ ...planned, status: 'executing', event: 'replanned' }),
      new Map(),
    );
    expect(re).toMatchObject({ status: 'replanned' });
    expect(plannedPose(profile, bytes({ ...planned, status: 'done' }), new Map())).toBeNull();
    expect(
      plannedPose(profile, bytes({ ...planned, status: 'executing', event: 'started' }), new Map()),
    ).toBeNull();
    expect(plannedPose(profile, new TextEncoder().encode('{not json'), new Map())).toBe(
      'unreadable',
    );
    expect(plannedPose(profile, bytes({ ...planned, end: 7 }), new Map())).toBe('unreadable');
  });

  test("ArmFeed: /{arm}/plan at the arm's time, and /{arm}/plan_tf hung off the arm's root", () => {
    const f = new ArmFeed('arm1', profile, urdf.joints);
    const out = f.feed('arm/arm1/feedback', bytes(planned), 5);
    expect(out.map((m) => m.kind)).toEqual(['plan', 'plan_tf']);
    expect(out[0]!.ns).toBe(1_700_000_000_500_000_000n);
    type T = { parent_frame_id: string; child_frame_id: string };
    const tf = (out[1]!.body as { transforms: T[] }).transforms;
    const root = urdf.joints[0]!.parent;
    expect(tf[0]).toMatchObject({ parent_frame_id: root, child_frame_id: `plan/${root}` });
    expect(tf.slice(1).map((t) => t.child_frame_id)).toEqual(
      urdf.joints.map((j) => `plan/${j.child}`),
    );
    expect(f.feed('arm/arm1/feedback', bytes('junk'), 5)).toEqual([]);
    expect(f.counts.unreadable).toBe(1);
  });
});
