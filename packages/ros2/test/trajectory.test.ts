/**
 * A JointTrajectory as armtwin frames: from the reported pose through each point at its time,
 * named joints only, angle servos as angle frames, an empty trajectory a stop, and every
 * malformed trajectory refused whole with its reason.
 */
import { describe, expect, test } from 'vitest';
import { exactPwmFromServo } from '@armtwin/motion';
import { createReader, type Frame } from '@armtwin/protocol';
import { trajectoryFrames } from '../src/trajectory.ts';
import { armtwin5 } from './profiles.ts';

const { profile, robot } = armtwin5();
const home = profile.servos.map(() => 1500);
const frames = (text: string): Frame[] => {
  const out: Frame[] = [];
  createReader({ onFrame: (f) => out.push(f), onGroup: (g) => out.push(...g.frames) }).feed(text);
  return out;
};

describe('trajectoryFrames', () => {
  test('streams the named joints through each point, ending exactly at the last one', () => {
    const r = trajectoryFrames(
      profile,
      robot.table,
      home,
      {
        joint_names: ['elbow', 'shoulder'],
        points: [
          { positions: [-0.5, 0.2], time_from_start_ms: 300 },
          { positions: [-1.0, 0.4], time_from_start_ms: 600 },
        ],
      },
      100,
    );
    if (r.kind !== 'move') throw new Error(r.kind);
    expect(r.durationMs).toBe(600);
    expect(r.frames.map((f) => f.at)).toEqual([0, 100, 200, 300, 400, 500]);
    const last = frames(r.frames.at(-1)!.frame);
    const pwmOf = (id: number) => last.find((f) => f.type === 'move' && f.id === id);
    const elbow = profile.servos[2]!;
    const shoulder = profile.servos[1]!;
    expect(pwmOf(2)).toMatchObject({
      pwm: Math.round(exactPwmFromServo(elbow, (-1.0 * 180) / Math.PI)),
      ms: 100,
    });
    expect(pwmOf(1)).toMatchObject({
      pwm: Math.round(exactPwmFromServo(shoulder, (0.4 * 180) / Math.PI)),
    });
    // Joints it does not name are never sent.
    expect(
      r.frames
        .flatMap((f) => frames(f.frame))
        .every((f) => f.type === 'move' && (f.id === 1 || f.id === 2)),
    ).toBe(true);
  });

  test('an angle servo is sent angle frames', () => {
    const raw = {
      ...profile,
      servos: profile.servos.map((s, i) => (i === 4 ? { ...s, units: 'angle' as const } : s)),
    };
    const units = robot.table.map((t, i) => (i === 4 ? { ...t, units: 'angle' as const } : t));
    const r = trajectoryFrames(
      raw,
      units,
      home,
      {
        joint_names: ['wrist_roll'],
        points: [{ positions: [Math.PI / 2], time_from_start_ms: 100 }],
      },
      100,
    );
    if (r.kind !== 'move') throw new Error(r.kind);
    expect(frames(r.frames[0]!.frame)).toEqual([{ type: 'angleMove', id: 4, deg: 90, ms: 100 }]);
  });

  test('an empty trajectory stops the joints it names (all when it names none)', () => {
    expect(
      trajectoryFrames(profile, robot.table, home, { joint_names: ['elbow'], points: [] }, 100),
    ).toEqual({ kind: 'stop', ids: [2] });
    expect(
      trajectoryFrames(profile, robot.table, home, { joint_names: [], points: [] }, 100),
    ).toEqual({ kind: 'stop', ids: [0, 1, 2, 3, 4, 5] });
  });

  test.each([
    [
      'unknown-joint',
      { joint_names: ['knee'], points: [{ positions: [0], time_from_start_ms: 100 }] },
      home,
    ],
    [
      'bad-point',
      { joint_names: ['elbow', 'base_yaw'], points: [{ positions: [0], time_from_start_ms: 100 }] },
      home,
    ],
    [
      'bad-time',
      { joint_names: ['elbow'], points: [{ positions: [0], time_from_start_ms: 0 }] },
      home,
    ],
    [
      'bad-time',
      {
        joint_names: ['elbow'],
        points: [
          { positions: [0], time_from_start_ms: 200 },
          { positions: [0.1], time_from_start_ms: 200 },
        ],
      },
      home,
    ],
    [
      'out-of-range',
      { joint_names: ['elbow'], points: [{ positions: [4], time_from_start_ms: 100 }] },
      home,
    ],
    [
      'no-state',
      { joint_names: ['elbow'], points: [{ positions: [0], time_from_start_ms: 100 }] },
      home.map((p, i) => (i === 3 ? NaN : p)),
    ],
  ] as const)('refused: %s', (reason, traj, pose) => {
    const r = trajectoryFrames(
      profile,
      robot.table,
      pose,
      {
        joint_names: [...traj.joint_names],
        points: traj.points.map((p) => ({ ...p, positions: [...p.positions] })),
      },
      100,
    );
    expect(r).toMatchObject({ kind: 'refused', reason });
    expect(r.kind === 'refused' && r.message.length).toBeGreaterThan(10);
  });
});
