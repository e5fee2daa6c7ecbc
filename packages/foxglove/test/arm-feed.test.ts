import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { jointFromPwm, parseUrdfJoints } from '@armtwin/robot';
import { ArmFeed } from '../src/arm-feed.ts';

const { profile } = readRobotFolder('armtwin5');
const urdf = parseUrdfJoints(
  fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', profile.urdf), 'utf8'),
);
if (!urdf.ok) throw new Error(urdf.errors.join('; '));
const feed = () => new ArmFeed('arm1', profile, urdf.joints);
const bytes = (s: string) => new TextEncoder().encode(s);
const group = (pwm: number[]) =>
  `{${pwm.map((p, i) => `#${String(profile.servos[i]!.id).padStart(3, '0')}P${p}!`).join('')}}`;

describe('ArmFeed', () => {
  test("a status payload gives joint states and transforms at the arm's own stamp", () => {
    const f = feed();
    const pwm = [1500, 1600, 1400, 1500, 1500, 1500];
    const out = f.feed('arm/arm1/status', bytes(`$TIM:1700000000123!${group(pwm)}`), 5);
    expect(out.map((m) => m.kind)).toEqual(['joint_states', 'tf']);
    expect(out[0]!.ns).toBe(1_700_000_000_123_000_000n);
    const joints = (out[0]!.body as { joints: { name: string; position: number }[] }).joints;
    expect(joints[1]).toEqual({
      name: 'shoulder',
      position: jointFromPwm(profile.servos[1]!, 1600),
    });
    const tf = (out[1]!.body as { transforms: { child_frame_id: string }[] }).transforms;
    expect(tf.map((t) => t.child_frame_id)).toEqual(urdf.joints.map((j) => j.child));
  });

  test('nothing until every servo reported; health, targets and the log as they come', () => {
    const f = feed();
    expect(f.feed('arm/arm1/status', bytes('$TIM:1000!#001P1500!'), 0)).toEqual([]);
    const [health] = f.feed('arm/arm1/status', bytes('$TIM:2000!#002T070V7400!'), 0);
    expect(health!.body).toMatchObject({
      id: '002',
      joint: 'elbow',
      temp: 70,
      volt: 7.4,
      level: 'warning',
    });
    const [target] = f.feed('arm/arm1/control/alice', bytes('#000P1600T0500!'), 3000);
    const joints = (target!.body as { joints: { name: string; position: number; ms: number }[] })
      .joints;
    // every joint in servo order: the moved one with its ms, the others where they stand
    expect(target!.body).toMatchObject({ by: 'alice' });
    expect(joints.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    expect(joints.map((j) => j.ms)).toEqual(profile.servos.map((s) => (s.id === 0 ? 500 : 0)));
    expect(joints[0]!.position).toBeCloseTo(jointFromPwm(profile.servos[0]!, 1600), 12);
    expect(target!.ns).toBe(3_000_000_000n);
    const audit = { at: 4000, by: 'bob', kind: 'refused-command', detail: 'controlled by alice' };
    const [log] = f.feed('arm/arm1/audit', bytes(JSON.stringify(audit)), 0);
    expect(log!.body).toMatchObject({ level: 3, message: 'refused-command: controlled by alice' });
    expect(f.feed('arm/arm1/audit', bytes('{"nope":1}'), 0)).toEqual([]);
    expect(f.counts.unreadable).toBe(1);
  });
});
