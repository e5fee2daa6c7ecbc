/**
 * Teaching by showing: a recorded stretch of an arm's motion (timed pulse vectors, e.g. the
 * history API's pose frames) → the fewest timed joint waypoints whose plan reproduces it.
 *
 * The plan a taught list runs is a joint plan with the `linear` profile and each target timed
 * (`TargetTiming`): between two waypoints every servo moves at constant speed, straight in
 * pulses, taking the recorded time; at a stop it holds for the recorded dwell. So the error is
 * measured exactly as that plan would run: at each recorded sample's time, the recorded pose
 * against the plan's. Steps:
 * 1. Stops: runs of at least `dwellMs` where every servo stays within `still…` of the run's
 *    first sample. A stop becomes one waypoint (the mean pose, held for the run), its samples
 *    are dropped. A stop at the very start or end is where the plan starts or ends.
 * 2. Between stops, Ramer–Douglas–Peucker in (time, pulses): the segment between the two ends
 *    is kept while every sample in between is within tolerance of it (each servo within
 *    `jointDeg`/`jointMm`, the tip within `tipMm` by FK); otherwise it is split at the worst
 *    sample. Reversals and other changes of motion are where those splits fall; noise well
 *    inside the tolerance adds none.
 * Pure: no I/O. The result says how far the taught plan is from the recording (max and mean).
 */
import type { MotionRobot } from './robot.ts';
import { Metric } from './teach-metric.ts';

export interface TeachOptions {
  /** Largest error allowed for a revolute servo at any recorded sample, degrees. */
  jointDeg: number;
  /** … for a prismatic axis, mm. */
  jointMm: number;
  /** Largest tip position error allowed at any recorded sample, mm (FK). */
  tipMm: number;
  /** A stop: every revolute servo stays within this of where the stop began, degrees. */
  stillDeg: number;
  /** … every prismatic axis, mm. */
  stillMm: number;
  /** … for at least this long, ms. */
  dwellMs: number;
  /** More waypoints than this is refused (a motion request takes 64 targets). */
  maxWaypoints: number;
}

export const DEFAULT_TEACH_OPTIONS: Readonly<TeachOptions> = {
  jointDeg: 2,
  jointMm: 2,
  tipMm: 5,
  stillDeg: 0.5,
  stillMm: 0.5,
  dwellMs: 300,
  maxWaypoints: 64,
};

export interface Recording {
  /** Sample times, ms, ascending (any origin; epoch ms from the history API). */
  readonly times: readonly number[];
  /** `pwm[k][i]`: servo i's pulse (µs, profile order) at `times[k]`; null or NaN = not known. */
  readonly pwm: readonly (readonly (number | null)[])[];
}

export interface TaughtWaypoint {
  /** Pulses, profile order (NaN: a servo the recording never saw; the plan leaves it). */
  pwm: number[];
  /** When the recorded arm got here, ms after the recording's first sample. */
  t: number;
  /** From leaving the previous waypoint to arriving here, ms (0 for the first). */
  durationMs: number;
  /** How long the recorded arm stood here before moving on, ms (0 at the ends). */
  holdMs: number;
}

export interface TeachError {
  /** Largest / mean (over samples) revolute servo error, degrees. */
  maxDeg: number;
  meanDeg: number;
  /** Largest prismatic axis error, mm (0 without one). */
  maxMm: number;
  /** Largest / mean tip position error, mm. */
  maxTipMm: number;
  meanTipMm: number;
}

export type TeachOutcome =
  | { ok: true; waypoints: TaughtWaypoint[]; samples: number; error: TeachError }
  | { ok: false; samples: number; error: string };

/** A recording cleaned up: ascending distinct times from 0, every pulse known. */
interface Clean {
  t: number[];
  q: number[][];
  /** Servos with no sample at all (filled with home, NaN in the waypoints). */
  unseen: boolean[];
}

function clean(robot: MotionRobot, rec: Recording): Clean {
  const n = robot.table.length;
  const t: number[] = [];
  const q: (number | null)[][] = [];
  rec.times.forEach((time, k) => {
    const row = rec.pwm[k];
    if (!Number.isFinite(time) || !row) return;
    if (t.length > 0 && time <= t[t.length - 1]!) return;
    t.push(time);
    q.push(Array.from({ length: n }, (_, i) => (Number.isFinite(row[i]) ? row[i]! : null)));
  });
  const unseen = new Array<boolean>(n).fill(true);
  for (let i = 0; i < n; i++) {
    let last: number | null = null;
    for (const row of q) last = row[i] = row[i] ?? last; // forward fill
    const first = q.find((row) => row[i] !== null)?.[i] ?? null;
    unseen[i] = first === null;
    for (const row of q) {
      if (row[i] !== null) break;
      row[i] = first ?? robot.table[i]!.homePwm; // back fill the start
    }
  }
  const t0 = t[0] ?? 0;
  return { t: t.map((x) => x - t0), q: q as number[][], unseen };
}

/** A waypoint while it is built: its pose, arrival and departure times, sample indices. */
interface Key {
  pwm: number[];
  arrive: number;
  leave: number;
  first: number;
  last: number;
}

/** Stops (step 1): each a Key spanning its samples. */
function findStops(c: Clean, m: Metric, o: TeachOptions): Key[] {
  const stops: Key[] = [];
  const n = c.t.length;
  let i = 0;
  while (i < n) {
    let j = i;
    while (j + 1 < n && m.still(c.q[j + 1]!, c.q[i]!)) j++;
    if (j > i && c.t[j]! - c.t[i]! >= o.dwellMs) {
      const run = c.q.slice(i, j + 1);
      const mean = run[0]!.map((_, s) => run.reduce((sum, row) => sum + row[s]!, 0) / run.length);
      // The mean is the best pose to hold, unless (with the tip) it is out of tolerance.
      const pose = [mean, c.q[i]!].find((p) => run.every((row) => m.ratio(row, p) <= 1));
      if (pose) {
        stops.push({ pwm: [...pose], arrive: c.t[i]!, leave: c.t[j]!, first: i, last: j });
        i = j + 1;
        continue;
      }
    }
    i++;
  }
  return stops;
}

/**
 * When the arm reached (or left) a stop between two samples: the last moving samples (a, then
 * b further out) extrapolated at their speed to the stop's pose, along the fastest servo.
 * Returns the time, within [t(a), t(edge)] (the stop's first or last sample), and never closer
 * to t(a) than the servos at their top speed need between the stop's pose and sample a's: the
 * taught plan runs each segment in its time only if the servos can (the planner stretches a
 * segment that is too short, and the rest of the plan then runs late).
 */
function crossing(c: Clean, m: Metric, stop: Key, a: number, b: number, edge: number): number {
  const ta = c.t[a]!;
  const te = c.t[edge]!;
  if (b < 0 || b >= c.t.length) return te;
  const qa = c.q[a]!;
  const qb = c.q[b]!;
  let s = 0;
  for (let i = 1; i < qa.length; i++)
    if (Math.abs(qa[i]! - qb[i]!) > Math.abs(qa[s]! - qb[s]!)) s = i;
  const v = (qa[s]! - qb[s]!) / Math.abs(ta - c.t[b]!); // µs per ms, away from b
  if (Math.abs(v) < 1e-9) return te;
  const tau = (stop.pwm[s]! - qa[s]!) / v;
  const span = Math.abs(te - ta);
  // The fastest servo is there already, but the sample as a whole is not within tolerance of
  // the stop (another servo, or the tip): the arm reached it between the two samples, not at
  // sample a (a waypoint at a and the stop at the same instant would be a jump in no time).
  const guess = tau <= 0 && m.ratio(qa, stop.pwm) > 1 ? span / 2 : Math.max(0, tau);
  const dt = Math.min(span, Math.max(guess, m.travelMs(qa, stop.pwm)));
  return te > ta ? ta + dt : ta - dt;
}

/**
 * Stops' arrival and departure times refined between samples, where the sample next to the stop
 * is a moving one (not another stop's). A stop's own samples stay within [arrive, leave].
 */
function refine(c: Clean, m: Metric, stops: Key[]): void {
  stops.forEach((k, j) => {
    const prevLast = stops[j - 1]?.last ?? -1;
    const nextFirst = stops[j + 1]?.first ?? c.t.length;
    if (k.first - 1 > prevLast) k.arrive = crossing(c, m, k, k.first - 1, k.first - 2, k.first);
    if (k.last + 1 < nextFirst) k.leave = crossing(c, m, k, k.last + 1, k.last + 2, k.last);
  });
}

const sampleKey = (c: Clean, k: number): Key => ({
  pwm: [...c.q[k]!],
  arrive: c.t[k]!,
  leave: c.t[k]!,
  first: k,
  last: k,
});

/** Pose of the plan through `keys` at time t (linear between departure and arrival), into out. */
function poseAt(keys: readonly Key[], t: number, out: number[]): number[] {
  let k = 0;
  while (k + 1 < keys.length && keys[k + 1]!.arrive <= t) k++;
  const a = keys[k]!;
  const b = keys[k + 1];
  out.length = a.pwm.length;
  if (!b || t <= a.leave) {
    for (let i = 0; i < a.pwm.length; i++) out[i] = a.pwm[i]!;
    return out;
  }
  const u = (t - a.leave) / (b.arrive - a.leave);
  for (let i = 0; i < a.pwm.length; i++) out[i] = a.pwm[i]! + (b.pwm[i]! - a.pwm[i]!) * u;
  return out;
}

/** Step 2: the keys between a and b that keep every sample between them within tolerance. */
function simplify(c: Clean, m: Metric, a: Key, b: Key, out: Key[]): void {
  const stack: [Key, Key][] = [[a, b]];
  const found: Key[] = [];
  const scratch: number[] = [];
  while (stack.length > 0) {
    const [ka, kb] = stack.pop()!;
    let worst = 1;
    let at = -1;
    for (let k = ka.last + 1; k < kb.first; k++) {
      const r = m.ratio(c.q[k]!, poseAt([ka, kb], c.t[k]!, scratch));
      if (r > worst) {
        worst = r;
        at = k;
      }
    }
    if (at < 0) continue;
    const mid = sampleKey(c, at);
    found.push(mid);
    stack.push([ka, mid], [mid, kb]);
  }
  out.push(...found.sort((x, y) => x.first - y.first));
}

/** How far the plan through `keys` is from the recording, sample by sample. */
function measure(c: Clean, m: Metric, keys: readonly Key[]): TeachError {
  const e: TeachError = { maxDeg: 0, meanDeg: 0, maxMm: 0, maxTipMm: 0, meanTipMm: 0 };
  const p: number[] = [];
  c.t.forEach((t, k) => {
    poseAt(keys, t, p);
    const q = c.q[k]!;
    let deg = 0;
    for (let i = 0; i < q.length; i++) {
      const err = m.joint(i, q[i]!, p[i]!);
      if (m.prismatic[i]) e.maxMm = Math.max(e.maxMm, err);
      else deg = Math.max(deg, err);
    }
    const tip = m.tipMm(q, p);
    e.maxDeg = Math.max(e.maxDeg, deg);
    e.meanDeg += deg / c.t.length;
    e.maxTipMm = Math.max(e.maxTipMm, tip);
    e.meanTipMm += tip / c.t.length;
  });
  return e;
}

/** The fewest timed waypoints that reproduce `rec` within the tolerances (see the top). */
export function teachFromRecording(
  robot: MotionRobot,
  rec: Recording,
  options: Partial<TeachOptions> = {},
): TeachOutcome {
  const o = { ...DEFAULT_TEACH_OPTIONS, ...options };
  const c = clean(robot, rec);
  const samples = c.t.length;
  if (samples < 2)
    return {
      ok: false,
      samples,
      error: `${samples} pose sample(s) in the range; at least 2 needed`,
    };
  const m = new Metric(robot, o);
  const stops = findStops(c, m, o);
  refine(c, m, stops);
  const ends: Key[] = [...stops];
  if (ends[0]?.first !== 0) ends.unshift(sampleKey(c, 0));
  if (ends[ends.length - 1]!.last !== samples - 1) ends.push(sampleKey(c, samples - 1));
  const keys: Key[] = [ends[0]!];
  for (let k = 1; k < ends.length; k++) {
    simplify(c, m, ends[k - 1]!, ends[k]!, keys);
    keys.push(ends[k]!);
  }
  if (keys.length < 2) return { ok: false, samples, error: 'the arm did not move in this stretch' };
  if (keys.length > o.maxWaypoints)
    return {
      ok: false,
      samples,
      error: `the motion needs ${keys.length} waypoints to stay within ${o.jointDeg}° and ${o.tipMm} mm; at most ${o.maxWaypoints}: choose a shorter stretch`,
    };
  const error = measure(c, m, keys);
  const last = keys.length - 1;
  const waypoints = keys.map((k, i) => ({
    pwm: k.pwm.map((p, s) => (c.unseen[s] ? NaN : p)),
    // The plan starts when the recorded motion does and ends when it stops.
    t: i === 0 ? k.leave : k.arrive,
    durationMs: i === 0 ? 0 : k.arrive - keys[i - 1]!.leave,
    holdMs: i === 0 || i === last ? 0 : k.leave - k.arrive,
  }));
  return { ok: true, waypoints, samples, error };
}
