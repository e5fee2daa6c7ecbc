/** Re-exports for the tests, plus a named pose as exact pulses filled from home. */
import { exactPwmFromServo, type MotionRobot } from '../src/index.ts';
export * from '../src/index.ts';

export function posePwmOf(robot: MotionRobot, name: string): number[] {
  const values = robot.profile.poses[name]!;
  return robot.profile.servos.map((s, i) =>
    Number.isNaN(values[i]) ? robot.table[i]!.homePwm : exactPwmFromServo(s, values[i]!),
  );
}
