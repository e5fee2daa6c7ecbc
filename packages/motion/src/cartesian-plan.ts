/**
 * Cartesian-path plans: the tip moves along straight lines from where it is through each
 * waypoint in turn, with IK at every step (every `stepMm`, each solve seeded with the step
 * before, so the arm keeps its configuration). The pitch, when the waypoints give one (or on
 * the 5-axis arm, always: its IK needs one), is interpolated along each line from the pitch at
 * the line's start. The time of each step is the longer of: the step at `linearSpeed` (ramped
 * up from and down to rest over `accelMs`), and the time the slowest servo needs to make its
 * change at its speed limit (× `speed`). So a plan never exceeds a speed limit; near a
 * singularity it slows down instead. A step the IK cannot solve fails the plan with the IK
 * code and the waypoint and step it failed at.
 */
import { topSpeed } from './joint-plan.ts';
import { DEFAULT_PLAN_OPTIONS, type PlanOptions } from './options.ts';
import type { Plan, PlanSample } from './plan.ts';
import {
  planHeading,
  solveTip,
  tipPose,
  type MotionRobot,
  type TipPose,
  type TipTarget,
} from './robot.ts';

/** A Cartesian waypoint: where the tip goes, and the other servos (NaN = as they were). */
export interface CartesianWaypoint {
  tip: TipTarget;
  /** Pulses for the servos the IK does not drive (gripper, wrist roll), reached at the waypoint. */
  others?: readonly number[];
}

export type PlanResult =
  | { ok: true; plan: Plan }
  | {
      ok: false;
      /** IK status code (§4's, or the numeric solver's). */
      code: number;
      /** The waypoint (target index) whose line failed. */
      target: number;
      /** The step along that line (1 … steps), when a step failed. */
      step?: number;
      steps?: number;
      message: string;
    };

/** Pitch to try on a 5-axis arm: the interpolated one first, then by distance from it. */
function* pitchesNear(alpha: number): Generator<number> {
  const a = Math.max(-90, Math.min(90, alpha));
  yield a;
  for (let k = 1; k <= 180; k++) {
    if (a + k <= 90) yield a + k;
    if (a - k >= -90) yield a - k;
    if (a + k > 90 && a - k < -90) return;
  }
}

export function planCartesian(
  robot: MotionRobot,
  from: readonly number[],
  waypoints: readonly CartesianWaypoint[],
  options: Partial<PlanOptions> = {},
  describeCode: (code: number) => string = (c) => `code ${c}`,
): PlanResult {
  const o = { ...DEFAULT_PLAN_OPTIONS, ...options };
  const n = from.length;
  const analytic = robot.kind === 'analytic5';
  const heading = planHeading(robot, from);
  // Where each line starts: the tip now, then each waypoint exactly as asked.
  const start = tipPose(robot, from);
  let total = 0;
  let prev: TipPose = start;
  const ends: { p: TipPose; pitchGiven: boolean }[] = [];
  for (const [w, wp] of waypoints.entries()) {
    let pitch = wp.tip.pitch;
    if (pitch === undefined && analytic) {
      // The 5-axis IK needs a pitch: use the one §4's search picks at the waypoint.
      const r = solveTip(robot, wp.tip, from);
      if (r.code !== 0)
        return {
          ok: false,
          code: r.code,
          target: w,
          message: `targets[${w}]: ${describeCode(r.code)}`,
        };
      pitch = tipPose(
        robot,
        r.pwm.map((v, i) => (Number.isNaN(v) ? from[i]! : v)),
      ).pitch;
    }
    const p = { x: wp.tip.x, y: wp.tip.y, z: wp.tip.z, pitch: pitch ?? NaN };
    total += Math.hypot(p.x - prev.x, p.y - prev.y, p.z - prev.z);
    ends.push({ p, pitchGiven: pitch !== undefined });
    prev = p;
  }
  const stepMm = Math.max(o.stepMm, total / o.maxSteps);
  const vLin = o.linearSpeed / 1000; // mm per ms
  const accel = vLin / Math.max(1e-6, o.accelMs);
  const samples: PlanSample[] = [{ t: 0, pwm: [...from] }];
  const targetTimes: number[] = [];
  let at = [...from];
  let t = 0;
  prev = start;
  for (const [w, { p, pitchGiven }] of ends.entries()) {
    const dx = p.x - prev.x,
      dy = p.y - prev.y,
      dz = p.z - prev.z;
    const len = Math.hypot(dx, dy, dz);
    const pitch0 = !pitchGiven
      ? NaN
      : Number.isNaN(prev.pitch)
        ? tipPose(robot, at).pitch
        : prev.pitch;
    const dPitch = pitchGiven ? p.pitch - pitch0 : 0;
    const steps = Math.max(
      1,
      Math.ceil(len / stepMm - 1e-9),
      Math.ceil(Math.abs(dPitch) / o.stepDeg - 1e-9),
    );
    const segFrom = [...at];
    const others = waypoints[w]!.others;
    for (let k = 1; k <= steps; k++) {
      const u = k / steps;
      const target: TipTarget = { x: prev.x + dx * u, y: prev.y + dy * u, z: prev.z + dz * u };
      if (pitchGiven) target.pitch = pitch0 + dPitch * u;
      let r = solveTip(robot, target, at, heading);
      if (r.code !== 0 && analytic && !(k === steps && waypoints[w]!.tip.pitch !== undefined)) {
        // Keep the position on the line; let the pitch give way, as close to the plan as it
        // can (never at a waypoint whose pitch was asked for).
        for (const alpha of pitchesNear(target.pitch!)) {
          const r2 = solveTip(robot, { ...target, pitch: alpha }, at);
          if (r2.code === 0) {
            r = r2;
            break;
          }
        }
      }
      if (r.code !== 0)
        return {
          ok: false,
          code: r.code,
          target: w,
          step: k,
          steps,
          message: `targets[${w}] step ${k} of ${steps}: ${describeCode(r.code)}`,
        };
      const next = r.pwm.map((v, i) => {
        if (!Number.isNaN(v)) return v;
        const end = others?.[i];
        return end === undefined || Number.isNaN(end)
          ? segFrom[i]!
          : segFrom[i]! + (end - segFrom[i]!) * u;
      });
      // The step's time: the line at the (ramped) linear speed, or the slowest servo.
      const sMid = (len * (k - 0.5)) / steps;
      const ramp = Math.sqrt(2 * accel * Math.max(0, Math.min(sMid, len - sMid)));
      const v = Math.max(0.1 * vLin, Math.min(vLin, ramp));
      let dt = len / steps / v;
      for (let i = 0; i < n; i++)
        dt = Math.max(dt, Math.abs(next[i]! - at[i]!) / topSpeed(robot, i, o.speed));
      if (dt > 0) {
        t += dt;
        samples.push({ t, pwm: next });
      }
      at = next;
    }
    targetTimes.push(t);
    prev = { ...p, pitch: pitchGiven ? p.pitch : NaN };
  }
  return {
    ok: true,
    plan: { mode: 'cartesian', ids: robot.ids, samples, durationMs: t, targetTimes },
  };
}
