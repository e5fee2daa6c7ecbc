/**
 * The Cartesian panel's pure parts: the fields start at the active arm's tip (a point it
 * reaches, on the small demo arm and on the 3.7 m track6 alike), and a solution that would put
 * the hand under the floor is refused with code 24 and the reason, before anything is sent.
 */
import { describe, expect, test } from 'vitest';
import { DEMO_ARM } from '@armtwin/ik';
import { createMotionRobot, type MotionRobot } from '@armtwin/motion';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { solveTarget, startFields } from '../src/core/cartesian/solveTarget.ts';

const MODELS = new URL('../../../public/models', import.meta.url).pathname;
const load = (name: string): MotionRobot => readRobotFolder(name, MODELS).robot;
const home = (m: MotionRobot) => m.table.map((s) => s.homePwm);

describe('Cartesian target', () => {
  test.each(['armtwin5', 'track6', 'so101', 'so100'])(
    '%s: the fields start at the tip, which is reachable',
    (name) => {
      const m = load(name);
      const f = startFields(m, home(m));
      expect(startFields(m, new Float64Array(m.ids.length).fill(NaN))).toEqual(f); // not reported yet: home
      const r = solveTarget(Number(f.x), Number(f.y), Number(f.z), undefined, DEMO_ARM, m, home(m));
      expect(r.code).toBe(0);
      if (name === 'armtwin5') expect(f).toEqual({ x: '0', y: '0', z: '453', pitch: '' });
    },
  );

  test('no robot yet: blank fields', () => {
    expect(startFields(null, [])).toEqual({ x: '', y: '', z: '', pitch: '' });
  });

  test('a target the IK reaches with the hand under the floor: code 24, with the reason', () => {
    const m = createMotionRobot(load('armtwin5').profile);
    const r = solveTarget(200, 0, -50, undefined, DEMO_ARM, m, home(m));
    expect(r.code).toBe(24);
    expect(r.floor).toMatch(/^tip \d+\.\d mm below the floor \(z -\d+\.\d < 0\)$/);
    expect(solveTarget(200, 0, 20, undefined, DEMO_ARM, m, home(m)).code).toBe(0);
  });
});
