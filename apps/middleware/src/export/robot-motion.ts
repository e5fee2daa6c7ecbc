/**
 * The arm's motion in a recording as a robot tool shows it: the profile servos' URDF joint
 * values at each recorded instant (a `JointStates` sample), and every URDF joint's transform from
 * its parent link to its child link at those values (Foxglove's `FrameTransform`), so a 3D panel
 * draws the arm moving. Joint values follow the profile (`jointFromPwm`, or `jointFromServo` for
 * a bus servo's angle, PROTOCOL.md §8); URDF joints the profile does not drive stay at 0, a mimic
 * joint takes its master's value. Transforms: `linkTransforms` of @armtwin/robot. Pure.
 */
import { jointFromPwm, jointFromServo, type Profile } from '@armtwin/robot';
import type { ServoRow } from './recording.ts';

export interface JointSample {
  ns: bigint;
  /** URDF joint names of the profile's servos, in servo order. */
  names: readonly string[];
  /** Their values (rad, or m for a prismatic joint); NaN until the servo's first report. */
  positions: number[];
}

export { linkTransforms, type LinkTransform } from '@armtwin/robot';

/** The joint value a stored point gives servo `s`, or undefined if it holds no position. */
function jointValue(s: Profile['servos'][number], row: ServoRow): number | undefined {
  if (row.pwm !== undefined) return jointFromPwm(s, row.pwm);
  if (row.angle !== undefined) return jointFromServo(s, row.angle);
  return undefined;
}

/**
 * One sample per instant at which a profile servo reported a position (rows in time order); each
 * holds every servo's latest value, so a group's servos land in one sample.
 */
export function jointSamples(profile: Profile, rows: readonly ServoRow[]): JointSample[] {
  const index = new Map(profile.servos.map((s, i) => [s.id, i]));
  const names = profile.servos.map((s) => s.joint);
  const current = profile.servos.map(() => NaN);
  const out: JointSample[] = [];
  let open: bigint | null = null;
  const close = () => {
    if (open !== null) out.push({ ns: open, names, positions: [...current] });
    open = null;
  };
  for (const row of rows) {
    const i = index.get(Number(row.id));
    if (i === undefined) continue;
    const q = jointValue(profile.servos[i]!, row);
    if (q === undefined) continue;
    if (open !== null && row.ns !== open) close();
    current[i] = q;
    open = row.ns;
  }
  close();
  return out;
}

/**
 * The joints as commanded, one sample per command instant (`targets`: `jointSamples` of the
 * command rows), every joint filled: a servo not commanded yet in the range holds where it
 * stands, so it takes its latest reported value (`reported`: `jointSamples` of the servo rows).
 * Every sample then lists the same joints in the same order as the joint states.
 */
export function targetSamples(
  targets: readonly JointSample[],
  reported: readonly JointSample[],
): JointSample[] {
  let r = -1;
  return targets.map((t) => {
    while (r + 1 < reported.length && reported[r + 1]!.ns <= t.ns) r++;
    const stands = reported[r]?.positions;
    return {
      ...t,
      positions: t.positions.map((q, i) => (Number.isNaN(q) ? (stands?.[i] ?? NaN) : q)),
    };
  });
}
