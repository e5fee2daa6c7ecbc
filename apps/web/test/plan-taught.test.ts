/**
 * History → Plan panel: a recorded pose as the history API sends it (degrees at polarity 1,
 * columns by id, nulls before a servo's first sample, a column of a servo the profile lacks)
 * becomes a handful of taught waypoints; the plan the panel makes of them (planSpec, linear,
 * timed) passes the plan checks and goes through the recorded poses.
 */
import { describe, expect, test } from 'vitest';
import {
  planSpec,
  samplePlan,
  teachFromRecording,
  tipPose,
  type MotionRobot,
} from '@armtwin/motion';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { angleFromPwm } from '@armtwin/protocol';
import { Waypoints } from '../src/core/plan/Waypoints.ts';
import {
  isTaught,
  planTargets,
  recordingFromPose,
  waypointsFromTaught,
} from '../src/core/plan/taught.ts';

const MODELS = new URL('../../../public/models', import.meta.url).pathname;
const robot: MotionRobot = readRobotFolder('armtwin5', MODELS).robot;
const home = robot.table.map((s) => s.homePwm);

/** Home → A (stop) → B (stop), as `/history/pose` frames every 100 ms from epoch 1.7e12. */
function poseAnswer() {
  const a = home.map((p, i) => p + (i < 4 ? 150 : 0));
  const b = home.map((p, i) => p + (i < 4 ? -100 : i === 5 ? 200 : 0));
  const keys: [number, number[]][] = [
    [0, home],
    [800, home],
    [1400, a],
    [2400, a],
    [3000, b],
    [4000, b],
  ];
  const at = (t: number) => {
    const j = keys.findIndex(([kt]) => kt > t);
    if (j < 0) return keys[keys.length - 1]![1];
    const [t0, p0] = keys[j - 1]!;
    const [t1, p1] = keys[j]!;
    return p0.map((p, i) => p + ((p1[i]! - p) * (t - t0)) / (t1 - t0));
  };
  const t0 = 1.7e12;
  const times: number[] = [];
  const angles: (number | null)[][] = [];
  for (let t = 0; t <= 4000; t += 100) {
    times.push(t0 + t);
    // Columns: 000–005 and 009 (not on this arm); the gripper (005) starts reporting late.
    angles.push([...at(t).map((p, i) => (i === 5 && t < 300 ? null : angleFromPwm(p))), 12]);
  }
  return { ids: ['000', '001', '002', '003', '004', '005', '009'], times, angles, a, b };
}

describe('taught waypoints in the Plan panel', () => {
  test('a recorded pose becomes three waypoints whose plan passes the checks and retraces it', () => {
    const rec = poseAnswer();
    const recording = recordingFromPose(robot, rec);
    expect(recording.pwm[0]).toHaveLength(robot.ids.length);
    expect(recording.pwm[0]![5]).toBeNull();
    const r = teachFromRecording(robot, recording);
    if (!r.ok) throw new Error(r.error);
    expect(r.waypoints).toHaveLength(3);

    const wp = new Waypoints();
    expect(wp.setTaught(waypointsFromTaught(robot, r.waypoints))).toBe(true);
    expect(wp.mode).toBe('joint');
    expect(isTaught(wp.list)).toBe(true);
    const tipA = tipPose(robot, rec.a);
    expect(wp.list[1]!.x).toBeCloseTo(tipA.x, 0);
    expect(wp.list[1]!.z).toBeCloseTo(tipA.z, 0);
    expect(wp.list[1]!.durationMs).toBeCloseTo(600, -1);
    expect(wp.list[1]!.holdMs).toBeCloseTo(1000, -1);

    const out = planSpec(
      robot,
      { mode: 'joint', targets: planTargets(wp.list), options: { speed: 0.3, profile: 'linear' } },
      home,
    );
    if (out.status !== 'planned') throw new Error(out.message);
    const plan = out.plan;
    // Home → first waypoint (home: no move), 600 ms to A, 1 s hold, 600 ms to B.
    const arriveA = plan.targetTimes[1]!;
    samplePlan(plan, arriveA + 500).forEach((p, i) => expect(p).toBeCloseTo(rec.a[i]!, 0));
    samplePlan(plan, plan.durationMs).forEach((p, i) => expect(p).toBeCloseTo(rec.b[i]!, 0));
    expect(plan.durationMs).toBeCloseTo(2200, -2);
  });

  test('moving a taught waypoint by hand makes it a plain tip waypoint', () => {
    const wp = new Waypoints();
    wp.setTaught([
      { x: 0, y: 0, z: 400, pwm: home },
      { x: 100, y: 0, z: 300, pwm: home, durationMs: 500 },
    ]);
    wp.move(1, { z: 250 });
    expect(wp.list[1]).toEqual({ x: 100, y: 0, z: 250 });
    expect(planTargets(wp.list)[1]).toEqual({ kind: 'tip', tip: { x: 100, y: 0, z: 250 } });
    expect(wp.setTaught([])).toBe(false);
  });
});
