import { describe, expect, test } from 'vitest';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { createReader, type Frame } from '@armtwin/protocol';
import { jointFromPwm } from '@armtwin/robot';
import { commandFrames, commandTopic } from '../src/commands.ts';

const folder = readRobotFolder('armtwin5');
const servos = folder.profile.servos;
const atRest = servos.map(() => 1500);
const json = (v: unknown) => new TextEncoder().encode(JSON.stringify(v));

/** The last pulse each servo is sent to in `frames`. */
function lastTargets(frames: { frame: string }[]): Map<number, number> {
  const out = new Map<number, number>();
  const on = (f: Frame) => f.type === 'move' && out.set(f.id, f.pwm);
  const reader = createReader({ onFrame: on, onGroup: (g) => g.frames.forEach(on) });
  for (const f of frames) reader.feed(f.frame);
  return out;
}

describe('commandTopic', () => {
  test('names the arm and the command, nothing else', () => {
    expect(commandTopic('/arm1/jog')).toEqual({ armId: 'arm1', command: 'jog' });
    expect(commandTopic('/arm-2/joint_trajectory')).toEqual({
      armId: 'arm-2',
      command: 'joint_trajectory',
    });
    expect(commandTopic('/arm1/tf')).toBeNull();
    expect(commandTopic('/Arm1/jog')).toBeNull();
  });
});

describe('commandFrames', () => {
  test('a jog moves one joint delta from where the arm reports it, in the time asked', () => {
    const elbow = servos.findIndex((s) => s.joint === 'elbow');
    const r = commandFrames(folder, atRest, 'jog', json({ joint: 'elbow', delta: 0.2, ms: 500 }));
    if (r.kind !== 'move') throw new Error(JSON.stringify(r));
    expect(r.durationMs).toBe(500);
    const target = lastTargets(r.frames).get(servos[elbow]!.id)!;
    const now = jointFromPwm(servos[elbow]!, 1500);
    expect(jointFromPwm(servos[elbow]!, target) - now).toBeCloseTo(0.2, 2);
  });

  test('a JointTrajectory with ROS times becomes timed frames; no points is a stop', () => {
    const r = commandFrames(
      folder,
      atRest,
      'joint_trajectory',
      json({
        joint_names: ['base_yaw'],
        points: [{ positions: [0.3], time_from_start: { sec: 1, nsec: 500_000_000 } }],
      }),
    );
    expect(r.kind === 'move' && r.durationMs).toBe(1500);
    const stop = commandFrames(
      folder,
      atRest,
      'joint_trajectory',
      json({ joint_names: [], points: [] }),
    );
    expect(stop.kind).toBe('stop');
  });

  test('bad input is refused with a reason, before any frame', () => {
    const cases: [unknown, RegExp][] = [
      [{ joint: 'knee', delta: 0.1 }, /knee is not in profile/],
      [{ joint: 'elbow' }, /jog needs/],
    ];
    for (const [v, why] of cases) {
      const r = commandFrames(folder, atRest, 'jog', json(v));
      expect(r.kind === 'refused' && r.message).toMatch(why);
    }
    const notJson = commandFrames(folder, atRest, 'jog', new TextEncoder().encode('{'));
    expect(notJson.kind === 'refused' && notJson.message).toMatch(/not JSON/);
    const unreported = commandFrames(
      folder,
      [NaN, ...atRest.slice(1)],
      'jog',
      json({ joint: 'base_yaw', delta: 0.1 }),
    );
    expect(unreported.kind === 'refused' && unreported.reason).toBe('no-state');
  });
});
