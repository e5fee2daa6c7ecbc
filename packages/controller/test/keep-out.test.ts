/**
 * Keep-out zones as the controller core checks them for every driver (docs/protocol.md,
 * "Keep-out zones"): `zonesKeepOut` checks a move in pulse-equivalents, here given in servo
 * degrees as a servo bus reads them: the floor at the goal, the zones and self-collision along
 * the straight path, the reason as `$ERR` text, '' when it may run.
 */
import fs from 'node:fs';
import { describe, expect, test } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import { createMotionRobot, exactPwmFromServo, type MotionRobot } from '@armtwin/motion';
import { zonesKeepOut } from '../src/index.ts';

/** The check in servo degrees (by servo index), as the bus driver hands the core its reads. */
function busZonesKeepOut(robot: MotionRobot) {
  const check = zonesKeepOut(robot);
  const pwm = (deg: readonly number[]) =>
    robot.profile.servos.map((s, i) => exactPwmFromServo(s, deg[i]!));
  return (from: readonly number[], to: readonly number[]) => check(pwm(from), pwm(to));
}

function armtwin5(keepOut: unknown) {
  const url = new URL('../../../public/models/armtwin5/profile.json', import.meta.url);
  const parsed = parseProfile({ ...JSON.parse(fs.readFileSync(url, 'utf8')), keepOut });
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  return createMotionRobot(parsed.profile);
}

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
const HOME = [0, 0, 0, 0, 0, 0];

describe('keep-out zones, the move given in servo degrees', () => {
  test('the hand into the table is refused, naming link and zone; a clear move is not', () => {
    const check = busZonesKeepOut(armtwin5({ zones: [TABLE] }));
    expect(check(HOME, [0, -45, -45, -90, 0, 0])).toMatch(/^zone: hand in "table"( on the way)?$/);
    expect(check(HOME, [0, -30, -60, -60, 0, 0])).toBe('');
    expect(check(HOME, [0, -90, -90, 0, 0, 0])).toMatch(/^floor: tip [\d.]+ mm below the floor/);
  });

  test('a base turn through a wall is refused on the way; from inside a zone the arm may leave', () => {
    const wall = { name: 'wall', shape: 'box', min: [100, -10, 0], max: [400, 10, 300] };
    const check = busZonesKeepOut(armtwin5({ zones: [wall, TABLE] }));
    expect(check([-90, -30, -60, -60, 0, 0], [90, -30, -60, -60, 0, 0])).toMatch(
      /^zone: (upper arm|forearm|hand) in "wall" on the way$/,
    );
    expect(check([0, -45, -45, -90, 0, 0], HOME)).toBe('');
  });
});
