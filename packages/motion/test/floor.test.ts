/**
 * The floor, the first keep-out zone (docs/protocol.md, "The floor"): `checkFloor` on poses,
 * plans refused with code 24 when any sample dips under it (joint and Cartesian, both IK
 * kinds), `ik.floorZ` moving it, and an arm already under it allowed to climb out.
 */
import fs from 'node:fs';
import { describe, expect, test } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import {
  CODE_BELOW_FLOOR,
  checkFloor,
  checkFloorMove,
  createMotionRobot,
  exactPwmFromServo,
  planRequest,
  type MotionRobot,
} from '../src/index.ts';
import { home, loadRobot } from './fixtures.ts';

const plan = (
  robot: MotionRobot,
  mode: 'joint' | 'cartesian',
  [x, y, z]: readonly [number, number, number],
) => planRequest(robot, { id: 'f', mode, targets: [{ x, y, z }], execute: true }, home(robot));

/** armtwin5 pulses for servo angles (deg) of servos 000–003; the rest at home. */
const pose = (robot: MotionRobot, deg: number[]) =>
  robot.profile.servos.map((s, i) => exactPwmFromServo(s, deg[i] ?? 0));

describe('the floor', () => {
  test.each([
    ['armtwin5', [200, 0, -50], [200, 0, 20]],
    ['track6', [1500, 0, -200], [1500, 0, 200]],
  ] as const)(
    '%s: a target under the floor is refused (24), above it planned',
    (name, low, high) => {
      const robot = loadRobot(name);
      expect(checkFloor(robot, home(robot))).toEqual({ ok: true });
      for (const mode of ['joint', 'cartesian'] as const) {
        const r = plan(robot, mode, low);
        expect(r).toMatchObject({ status: 'unreachable', code: CODE_BELOW_FLOOR, target: 0 });
        expect(r.message).toMatch(
          /^targets\[0\]: tip [\d.]+ mm below the floor \(z -[\d.]+ < 0\)$/,
        );
        expect(plan(robot, mode, high)).toMatchObject({ status: 'planned', code: 0 });
      }
    },
  );

  test('armtwin5: a joint pose (not only a tip target) is checked: forearm straight down', () => {
    const robot = loadRobot('armtwin5');
    // Upper arm level, forearm straight down: wrist at z 2, tip at z −148.
    expect(checkFloor(robot, pose(robot, [0, -90, -90, 0]))).toMatchObject({
      ok: false,
      point: 'tip',
    });
    const servos = { '001': -90, '002': -90 };
    const r = planRequest(
      robot,
      { id: 'j', mode: 'joint', targets: [{ unit: 'servo', servos }] },
      home(robot),
    );
    expect(r).toMatchObject({ status: 'unreachable', code: CODE_BELOW_FLOOR });
  });

  test('ik.floorZ moves the floor: a table-top arm with its floor 200 mm up refuses z 150', () => {
    const parsed = parseProfile({ ...rawProfile(), ik: { ...rawProfile().ik, floorZ: 200 } });
    expect(parsed.ok).toBe(true);
    if (!parsed.ok) return;
    expect(parsed.profile.ik.floorZ).toBe(200);
    const robot = createMotionRobot(parsed.profile);
    expect(plan(robot, 'joint', [150, 0, 150])).toMatchObject({ code: CODE_BELOW_FLOOR });
    expect(plan(loadRobot('armtwin5'), 'joint', [150, 0, 150])).toMatchObject({ code: 0 });
    expect(loadRobot('armtwin5').profile.ik.floorZ).toBeUndefined();
    expect(parseProfile({ ...rawProfile(), ik: { ...rawProfile().ik, floorZ: 'low' } })).toEqual({
      ok: false,
      errors: [expect.stringMatching(/^ik\.floorZ: must be a finite number/)],
    });
  });

  test('an arm already under the floor may climb out, never go lower', () => {
    const robot = loadRobot('armtwin5');
    const under = pose(robot, [0, -90, -60, 0]); // tip at z −115
    const lower = pose(robot, [0, -90, -90, 0]); // −148
    const higher = pose(robot, [0, -90, -30, 0]); // −24: still under, but climbing
    expect(checkFloorMove(robot, under, higher)).toEqual({ ok: true });
    expect(checkFloorMove(robot, under, lower)).toMatchObject({ ok: false, point: 'tip' });
    expect(checkFloorMove(robot, home(robot), under)).toMatchObject({ ok: false });
    const out = planRequest(robot, { id: 'u', mode: 'joint', targets: ['home'] }, under);
    expect(out).toMatchObject({ status: 'planned' });
  });
});

/** armtwin5's profile.json as shipped. */
function rawProfile(): { ik: Record<string, unknown> } & Record<string, unknown> {
  const url = new URL('../../../public/models/armtwin5/profile.json', import.meta.url);
  return JSON.parse(fs.readFileSync(url, 'utf8')) as { ik: Record<string, unknown> };
}
