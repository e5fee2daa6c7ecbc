/**
 * The shipped SO-101 (public/models/so101, imported from PyPI's example-robot-data): its FK
 * matches yourdfpy's (PyPI, not armtwin's code) on the same URDF within 0.1 mm over random
 * poses; its tool centre is the gripper frame and the gripper a tool joint, so a Cartesian move
 * (`$KMS`) to the simulated arm leaves the gripper where it was jogged while the arm moves.
 */
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { chainFk } from '@armtwin/ik';
import { MODELS_DIR } from '@armtwin/sim';
import { loadRobot, randomJoints, rng } from '../../packages/robot/test/numeric-fixtures.ts';
import { runLerobotScript } from '../helpers/lerobot-python.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const DIR = path.join(MODELS_DIR, 'so101');
const { profile, chain } = loadRobot('so101');

describe('the shipped SO-101', () => {
  test('its chain runs to the gripper frame; the gripper (id 6) is outside it', () => {
    expect(profile.ik).toMatchObject({ baseLink: 'base_link', tipLink: 'gripper_frame_link' });
    expect(chain.joints.map((j) => j.name)).toEqual([
      'shoulder_pan',
      'shoulder_lift',
      'elbow_flex',
      'wrist_flex',
      'wrist_roll',
    ]);
    expect(profile.servos.map((s) => [s.id, s.joint])).toEqual([
      [1, 'shoulder_pan'],
      [2, 'shoulder_lift'],
      [3, 'elbow_flex'],
      [4, 'wrist_flex'],
      [5, 'wrist_roll'],
      [6, 'gripper'],
    ]);
  });

  test("FK matches yourdfpy's within 0.1 mm and 0.01° over 300 random poses", () => {
    const next = rng(101);
    const poses = Array.from({ length: 300 }, () => randomJoints(chain, next));
    const gripper = profile.servos.findIndex((s) => s.joint === 'gripper');
    const theirs = runLerobotScript<number[][]>(
      'fk_yourdfpy.py',
      {
        urdf: path.join(DIR, profile.urdf),
        base: profile.ik.baseLink,
        tip: profile.ik.tipLink,
        // The gripper moves too (to any value): it must not move the tool centre.
        samples: poses.map((q, k) => ({
          ...Object.fromEntries(chain.joints.map((j, i) => [j.name, q[i]!])),
          [profile.servos[gripper]!.joint]: (k % 7) * 0.25,
        })),
      },
      'yourdfpy',
    );
    let worstMm = 0,
      worstDeg = 0;
    poses.forEach((q, k) => {
      const ours = chainFk(chain, q);
      const t = theirs[k]!;
      worstMm = Math.max(
        worstMm,
        Math.hypot(ours[12]! - t[12]! * 1000, ours[13]! - t[13]! * 1000, ours[14]! - t[14]! * 1000),
      );
      let trace = 0;
      for (let c = 0; c < 3; c++)
        for (let r = 0; r < 3; r++) trace += ours[c * 4 + r]! * t[c * 4 + r]!;
      worstDeg = Math.max(
        worstDeg,
        (Math.acos(Math.min(1, Math.max(-1, (trace - 1) / 2))) * 180) / Math.PI,
      );
    });
    expect(worstMm).toBeLessThan(0.1);
    expect(worstDeg).toBeLessThan(0.01);
  });
});

describe('the simulated SO-101: a Cartesian move leaves the gripper alone', () => {
  const broker = useMosquitto();
  const ARM = 'so101test';
  let sim: Child;
  let w: StatusWatcher;

  beforeAll(async () => {
    w = await StatusWatcher.connect(broker().url, ARM);
    sim = armtwin(['sim', '--mqtt', broker().url, '--arm', ARM, '--profile', 'so101']);
    await w.online();
  });

  afterAll(async () => {
    await sim?.stop('SIGKILL');
    await w?.close();
  });

  const latest = (id: number, from: number) => w.angleSamples(id, from).at(-1)?.[1];

  test('jog the gripper open, then $KMS: the arm goes, the gripper stays', async () => {
    let from = w.items.length;
    await w.send('#006A+030.00T0200!');
    await w.until(() => (latest(6, from) === 30 ? true : undefined), 5000, 'gripper at 30°');
    // A reachable point: the tool centre of a pose inside the limits.
    const tip = chainFk(chain, Float64Array.from([0.4, -0.3, 0.5, 0.6, 0]));
    from = w.items.length;
    const pan = latest(1, 0);
    await w.send(`$KMS:${tip[12]!.toFixed(1)},${tip[13]!.toFixed(1)},${tip[14]!.toFixed(1)},0500!`);
    const r = await w.frame((f) => f.type === 'kmsResult', from);
    expect(r.frame).toMatchObject({ code: 0 });
    await w.until(
      () => (w.angleSamples(1, from).some(([, d]) => d !== pan) ? true : undefined),
      5000,
      'the shoulder pan to move',
    );
    await w.until(
      () => (w.angleSamples(1, from).length > 80 ? true : undefined),
      5000,
      'the move to end',
    );
    expect(new Set(w.angleSamples(6, from).map(([, d]) => d))).toEqual(new Set([30]));
  });
});
