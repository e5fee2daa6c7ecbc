/**
 * From the history API's recorded pose to the Plan panel's waypoints, and from waypoints to the
 * planner's targets. Pure. The teaching itself (`teachFromRecording`) is @armtwin/motion's.
 */
import {
  tipPose,
  type MotionRobot,
  type Recording,
  type ResolvedTarget,
  type TaughtWaypoint,
} from '@armtwin/motion';
import { PWM_CENTRE, US_PER_DEG } from '@armtwin/protocol';
import type { PoseRecord } from '../replay/poseAt.ts';
import type { Waypoint } from './Waypoints.ts';

/**
 * A recorded pose (`/history/pose`: angles in degrees, the pulse's angle at polarity 1, columns
 * by three-digit id) as pulses in the robot's servo order. Columns of servos the robot does not
 * have are ignored; its servos without a column are unknown (null).
 */
export function recordingFromPose(
  robot: MotionRobot,
  rec: PoseRecord & { ids: readonly string[] },
): Recording {
  const column = robot.ids.map((id) =>
    rec.ids.findIndex((s) => /^\d{3}$/.test(s) && Number(s) === id),
  );
  return {
    times: rec.times,
    pwm: rec.angles.map((row) =>
      column.map((k) => {
        const a = k < 0 ? null : (row[k] ?? null);
        return a === null ? null : PWM_CENTRE + a * US_PER_DEG;
      }),
    ),
  };
}

/** Taught waypoints as the Plan panel's: the tip (FK, mm) shown, the pose and timing kept. */
export function waypointsFromTaught(
  robot: MotionRobot,
  taught: readonly TaughtWaypoint[],
): Waypoint[] {
  return taught.map((w, k) => {
    const full = w.pwm.map((p, i) => (Number.isFinite(p) ? p : robot.table[i]!.homePwm));
    const tip = tipPose(robot, full);
    const out: Waypoint = { x: tip.x, y: tip.y, z: tip.z, pwm: [...w.pwm] };
    // The first is reached from wherever the arm is, at the panel's speed.
    if (k > 0) {
      out.durationMs = w.durationMs;
      if (w.holdMs > 0) out.holdMs = w.holdMs;
    }
    return out;
  });
}

/** The planner's targets: a taught waypoint's pose (timed), or a tip target. */
export function planTargets(list: readonly Waypoint[]): ResolvedTarget[] {
  return list.map((w) => {
    if (!w.pwm) return { kind: 'tip', tip: { x: w.x, y: w.y, z: w.z } };
    const t: ResolvedTarget = { kind: 'joint', pwm: [...w.pwm] };
    if (w.durationMs !== undefined) t.durationMs = w.durationMs;
    if (w.holdMs !== undefined) t.holdMs = w.holdMs;
    return t;
  });
}

/** Whether any waypoint was taught (the plan then runs at the recorded pace: `linear`). */
export const isTaught = (list: readonly Waypoint[]): boolean => list.some((w) => w.pwm);
