/** Status payloads as ROS 2 joint states: radians (metres), URDF names, once every servo is known. */
import { expect, test } from 'vitest';
import { jointFromPwm } from '@armtwin/robot';
import { JointStateBuilder } from '../src/joint-states.ts';
import { armtwin5, track6 } from './profiles.ts';

test('a position group becomes one joint state with the $TIM stamp, in radians', () => {
  const b = new JointStateBuilder(armtwin5().profile);
  expect(b.feed('$TIM:1000!{#000P1500!#001P1600!#002P1400!}')).toBeUndefined(); // not every servo yet
  const js = b.feed('$TIM:1020!{#000P1500!#001P1600!#002P1400!#003P1500!#004P1500!#005A+045.00!}');
  expect(js?.name).toEqual([
    'base_yaw',
    'shoulder',
    'elbow',
    'wrist_pitch',
    'wrist_roll',
    'gripper',
  ]);
  expect(js?.stamp_ms).toBe(1020);
  expect(js?.position[1]).toBeCloseTo((((1600 - 1500) * 270) / 2000) * (Math.PI / 180), 12);
  expect(js?.position[5]).toBeCloseTo(Math.PI / 4, 12);
  expect(b.feed('#003T040V7400!')).toBeUndefined(); // health moves nothing
});

test('a prismatic axis is in metres; unknown servos are counted', () => {
  const { profile } = track6();
  const b = new JointStateBuilder(profile);
  const group = profile.servos.map((s) => `#${s.key}P1700!`).join('');
  const js = b.feed(`{${group}#200P1500!}`)!;
  profile.servos.forEach((s, i) => expect(js.position[i]).toBeCloseTo(jointFromPwm(s, 1700), 12));
  expect(profile.servos.some((s) => s.type === 'prismatic')).toBe(true);
  expect(b.unknownServo).toBe(1);
});
