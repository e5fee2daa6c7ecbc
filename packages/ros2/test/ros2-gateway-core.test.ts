/**
 * The ROS 2 gateway's core on a manual clock (no processes): joint states in as angle groups at
 * the state rate, presence from their freshness, and the controller core's goals and holds out
 * as trajectories. The controller's own rules are tested in @armtwin/controller and, on this
 * driver, by tests/integration/controller-behaviour.test.ts.
 */
import { expect, test } from 'vitest';
import { INVALID_PROFILE_REASON, refuseEveryMove } from '@armtwin/controller';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { servoFromJoint } from '@armtwin/robot';
import { HOLD_MS, Ros2GatewayCore, type JointTrajectoryMsg } from '../src/index.ts';
import { armtwin5, track6 } from './profiles.ts';

const NAMES = ['base_yaw', 'shoulder', 'elbow', 'wrist_pitch', 'wrist_roll', 'gripper'];

function setup() {
  const clock = new FakeClock();
  const published: { topic: string; payload: string }[] = [];
  const trajectories: JointTrajectoryMsg[] = [];
  const firsts: string[] = [];
  const core = new Ros2GatewayCore(
    { armId: 'a', profile: armtwin5().profile, stateRate: 50, staleMs: 500 },
    {
      ...clock,
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (h) => clock.clearTimeout(h),
      publish: (topic, payload) => published.push({ topic, payload }),
      trajectory: (m) => trajectories.push(m),
      onFirst: (_kind, message) => firsts.push(message),
    },
  );
  core.brokerConnected(true);
  core.start();
  return { clock, core, published, trajectories, firsts };
}

test('joint states become angle groups at the state rate; presence follows them', () => {
  const { clock, core, published, firsts } = setup();
  expect(core.fromJointState({ name: ['shoulder'], position: [0] })).toMatch(/without base_yaw/);
  core.fromJointState({ name: [...NAMES, 'wheel'], position: [0.1, 0, 0, 0, 0, 0, 9] });
  expect(firsts.join()).toMatch(/ignored: wheel/);
  clock.advance(20);
  const status = published.filter((p) => p.topic === 'arm/a/status').at(-1)!.payload;
  expect(status).toMatch(/^\$TIM:\d+!\{#000A\+005\.73!#001A\+000\.00!/);
  expect(published.filter((p) => p.topic === 'arm/a/online').map((p) => p.payload)).toEqual([
    '0',
    '1',
  ]);
  clock.advance(600);
  expect(published.filter((p) => p.topic === 'arm/a/online').map((p) => p.payload)).toEqual([
    '0',
    '1',
    '0',
  ]);
  core.fromControl('#001P1600T0300!');
  expect(published.at(-1)!.payload).toMatch(/\$ERR:ros2: no joint states!/);
});

test('a move is one trajectory point in its time; the e-stop holds where the joints are', () => {
  const { clock, core, trajectories } = setup();
  core.fromJointState({ name: NAMES, position: [0, 0.2, 0, 0, 0, 0] });
  core.fromControl('#001P1600T0300!');
  expect(trajectories.at(-1)!.joint_names).toEqual(['shoulder']);
  expect(trajectories.at(-1)!.points[0]!.time_from_start_ms).toBe(300);
  expect(trajectories.at(-1)!.points[0]!.positions[0]).toBeCloseTo(
    ((100 * 270) / 2000 / 180) * Math.PI,
    9,
  );
  clock.advance(100);
  core.fromJointState({ name: NAMES, position: [0, 0.21, 0, 0, 0, 0] });
  core.fromControl('#255PDST!');
  const hold = trajectories.at(-1)!;
  expect(hold.joint_names).toEqual(NAMES);
  expect(hold.points[0]!.positions[1]).toBeCloseTo(0.21, 9);
  expect(hold.points[0]!.time_from_start_ms).toBe(HOLD_MS);
});

test('an edited profile is put in force without a restart: zones, offsets; other joints refused', () => {
  const { core, published, trajectories } = setup();
  core.fromJointState({ name: NAMES, position: [0, 0.2, 0, 0, 0, 0] });
  const before = core.positions[1]!;
  const { profile } = armtwin5();
  const edited = {
    ...profile,
    servos: profile.servos.map((s, i) => (i === 1 ? { ...s, offset: 10 } : s)),
  };
  expect(core.reconfigure(edited, undefined, refuseEveryMove)).toBe('');
  expect(core.profile).toBe(edited);
  // the shoulder's last joint state, read through the new offset at once
  expect(core.positions[1]).toBeCloseTo(servoFromJoint(edited.servos[1]!, 0.2), 9);
  expect(core.positions[1]).not.toBeCloseTo(before, 3);
  core.fromControl('#001P1600T0300!');
  expect(published.at(-1)!.payload).toContain(`$ERR:${INVALID_PROFILE_REASON}!`);
  expect(trajectories).toEqual([]);
  // a profile on other joints needs a restart; the one in force stays
  expect(core.reconfigure(track6().profile)).toMatch(/restart the gateway/);
  expect(core.profile).toBe(edited);
});
