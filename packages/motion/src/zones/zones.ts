/**
 * Keep-out zones and self-collision (docs/protocol.md, "Keep-out zones"): the arm's moving
 * links, capsules of `linkRadius` around FK segments (arm-links.ts), must stay out of every
 * zone of the profile's `keepOut`, and links that are not neighbours must not touch. One pure
 * check, used by the page before it sends and again by the controllers before they move. A
 * move is checked along its straight joint-space path, sampled so no servo turns more than
 * `pathStepDeg` (or slides more than `pathStepMm`) between two checked poses.
 */
import { servoFromPwm, type ProfileKeepOut } from '@armtwin/robot';
import type { Plan } from '../plan.ts';
import type { MotionRobot } from '../robot.ts';
import { armLinks } from './arm-links.ts';
import { segmentSegmentDistance, segmentZoneDistance, zoneDistance } from './geometry.ts';

export interface ZoneOptions {
  /** Capsule radius of every link, mm, when the profile's `keepOut.linkRadius` is absent. */
  linkRadius: number;
  /**
   * Path sampling: the most any revolute servo turns between two checked poses, degrees. A link
   * point R mm from the axis moves R·π/180 mm per degree: 8 mm at armtwin5's full reach (453 mm).
   */
  pathStepDeg: number;
  /**
   * Path sampling: the most any prismatic axis slides between two checked poses, mm (a slide
   * moves every link by exactly this, a quarter of the default link radius).
   */
  pathStepMm: number;
}

export const DEFAULT_ZONE_OPTIONS: ZoneOptions = {
  linkRadius: 20,
  pathStepDeg: 1,
  pathStepMm: 5,
};

/** Depth still accepted, mm (rounding: a link exactly touching a zone passes). */
export const ZONE_TOLERANCE_MM = 1e-6;

/** One collision: a link in a zone (`zone`) or touching another link (`self`). */
export interface ZoneHit {
  ok: false;
  kind: 'zone' | 'self';
  /** The offending link (`forearm`, `a3 link`). */
  link: string;
  /** The URDF joint whose child link it is ('' for the base), for the ghost to paint. */
  joint: string;
  /** The zone's name, or the other link's. */
  other: string;
  /** How far in, mm. */
  depth: number;
  /** Along the move, 0…1 (1 = at the goal); 1 for a single pose. */
  at: number;
  /** In words: `forearm 12.3 mm into zone "table"`. */
  message: string;
}

export type ZoneCheck = { ok: true } | ZoneHit;

const OK: ZoneCheck = { ok: true };
const NO_HITS: ZoneHit[] = [];
const NONE: ProfileKeepOut = { zones: [] };

function keepOutOf(robot: MotionRobot, keepOut?: ProfileKeepOut): ProfileKeepOut {
  return keepOut ?? robot.profile.keepOut ?? NONE;
}

function radius(ko: ProfileKeepOut, o: Partial<ZoneOptions>): number {
  return ko.linkRadius ?? o.linkRadius ?? DEFAULT_ZONE_OPTIONS.linkRadius;
}

/**
 * Link pairs checked for self-collision: not neighbours, and apart at the home pose (pairs that
 * touch there touch by construction, as a motion planner's "adjacent" pairs), once per robot.
 */
const pairsCache = new WeakMap<MotionRobot, Map<number, Int32Array>>();
function selfPairs(robot: MotionRobot, r: number): Int32Array {
  let byR = pairsCache.get(robot);
  if (!byR) pairsCache.set(robot, (byR = new Map()));
  let pairs = byR.get(r);
  if (pairs) return pairs;
  const links = armLinks(
    robot,
    robot.table.map((s) => s.homePwm),
  );
  const out: number[] = [];
  if (links)
    for (let i = 0; i < links.count; i++)
      for (let j = i + 2; j < links.count; j++)
        if (segmentSegmentDistance(links.points, 3 * i, 3 * i + 3, 3 * j, 3 * j + 3) > 2 * r)
          out.push(i, j);
  pairs = Int32Array.from(out);
  byR.set(r, pairs);
  return pairs;
}

function hit(
  kind: ZoneHit['kind'],
  link: number,
  other: string,
  depth: number,
  names: readonly string[],
  joints: readonly string[],
): ZoneHit {
  const name = names[link]!;
  const into = kind === 'zone' ? `zone "${other}"` : `the ${other} (self-collision)`;
  return {
    ok: false,
    kind,
    link: name,
    joint: joints[link]!,
    other,
    depth,
    at: 1,
    message: `${name} ${depth.toFixed(1)} mm into ${into}`,
  };
}

/**
 * Every collision of the pose of these pulses (profile order), deepest first when `all`, else
 * the deepest one only (as a one-element list, or empty when clear). A pose with a servo of the
 * kinematic chain unknown (NaN) cannot be checked and passes.
 */
function collisions(
  robot: MotionRobot,
  pwm: ArrayLike<number>,
  ko: ProfileKeepOut,
  o: Partial<ZoneOptions>,
  all: boolean,
): ZoneHit[] {
  const r = radius(ko, o);
  const links = armLinks(robot, pwm);
  if (!links) return NO_HITS;
  const { points: p, names, joints, count } = links;
  let found: ZoneHit[] = NO_HITS;
  let best = ZONE_TOLERANCE_MM;
  // Allocation-free while clear: a hit (rare) builds its record. Broad phase: a sphere round
  // the moving links' points; a zone farther from its centre than its radius plus the links'
  // is clear of every link at the cost of one distance.
  let cx = 0,
    cy = 0,
    cz = 0;
  for (let k = 1; k <= count; k++) {
    cx += p[3 * k]!;
    cy += p[3 * k + 1]!;
    cz += p[3 * k + 2]!;
  }
  cx /= count;
  cy /= count;
  cz /= count;
  let reach = 0;
  for (let k = 1; k <= count; k++) {
    const dx = p[3 * k]! - cx,
      dy = p[3 * k + 1]! - cy,
      dz = p[3 * k + 2]! - cz;
    reach = Math.max(reach, dx * dx + dy * dy + dz * dz);
  }
  reach = Math.sqrt(reach) + r;
  const zones = ko.zones;
  for (let z = 0; z < zones.length; z++) {
    const zone = zones[z]!;
    if (zoneDistance(zone, cx, cy, cz) > reach) continue;
    for (let i = 1; i < count; i++) {
      const depth = r - segmentZoneDistance(zone, p, 3 * i, 3 * i + 3, r);
      if (all ? depth > ZONE_TOLERANCE_MM : depth > best) {
        found = all
          ? [...found, hit('zone', i, zone.name, depth, names, joints)]
          : [hit('zone', i, zone.name, depth, names, joints)];
        if (depth > best) best = depth;
      }
    }
  }
  if (ko.selfCollision !== false) {
    const pairs = selfPairs(robot, r);
    for (let k = 0; k < pairs.length; k += 2) {
      const i = pairs[k]!,
        j = pairs[k + 1]!;
      const depth = 2 * r - segmentSegmentDistance(p, 3 * i, 3 * i + 3, 3 * j, 3 * j + 3);
      // The link farther from the base is the one that moved into the other.
      if (all ? depth > ZONE_TOLERANCE_MM : depth > best) {
        found = all
          ? [...found, hit('self', j, names[i]!, depth, names, joints)]
          : [hit('self', j, names[i]!, depth, names, joints)];
        if (depth > best) best = depth;
      }
    }
  }
  return all ? [...found].sort((a, b) => b.depth - a.depth) : found;
}

/** Whether the pose of these pulses keeps every link out of every zone and off the others. */
export function checkZones(
  robot: MotionRobot,
  pwm: ArrayLike<number>,
  keepOut?: ProfileKeepOut,
  options: Partial<ZoneOptions> = {},
): ZoneCheck {
  return collisions(robot, pwm, keepOutOf(robot, keepOut), options, false)[0] ?? OK;
}

let lerp = new Float64Array(32);

/** The path from a clear pose `from` to `to`, sampled; the first collision on it. */
function checkPath(
  robot: MotionRobot,
  from: ArrayLike<number>,
  to: ArrayLike<number>,
  ko: ProfileKeepOut,
  o: Partial<ZoneOptions>,
): ZoneCheck {
  const stepDeg = o.pathStepDeg ?? DEFAULT_ZONE_OPTIONS.pathStepDeg;
  const stepMm = o.pathStepMm ?? DEFAULT_ZONE_OPTIONS.pathStepMm;
  const servos = robot.profile.servos;
  const n = servos.length;
  let steps = 1;
  for (let i = 0; i < n; i++) {
    const s = servos[i]!;
    const b = Number.isNaN(to[i]!) ? from[i]! : to[i]!;
    const d = Math.abs(servoFromPwm(s, b) - servoFromPwm(s, from[i]!));
    if (Number.isFinite(d))
      steps = Math.max(steps, Math.ceil(d / (s.type === 'revolute' ? stepDeg : stepMm)));
  }
  if (lerp.length < n) lerp = new Float64Array(n);
  const at = (k: number): ZoneCheck => {
    const f = k / steps;
    for (let i = 0; i < n; i++) {
      const a = from[i]!;
      const b = Number.isNaN(to[i]!) ? a : to[i]!;
      lerp[i] = a + (b - a) * f;
    }
    const c = collisions(robot, lerp, ko, o, false)[0];
    if (!c) return OK;
    return k === steps ? c : { ...c, at: f, message: `on the way: ${c.message}` };
  };
  // The goal first (a refusal then says how deep the move ends), then the path to it.
  const goal = at(steps);
  if (!goal.ok) return goal;
  for (let k = 1; k < steps; k++) {
    const c = at(k);
    if (!c.ok) return c;
  }
  return OK;
}

/**
 * A controller's rule for a move from pose `from` to pose `to` (pulses, profile order; NaN in
 * `to` = that servo stays): refused when any pose on the straight joint-space path between them
 * collides. From a pose that already collides (put there by hand, or a zone added around it),
 * only the goal is checked, and it passes when it is no deeper in anything than `from` was, so
 * the arm can always be brought out.
 */
export function checkZonesMove(
  robot: MotionRobot,
  from: ArrayLike<number>,
  to: ArrayLike<number>,
  keepOut?: ProfileKeepOut,
  options: Partial<ZoneOptions> = {},
): ZoneCheck {
  const ko = keepOutOf(robot, keepOut);
  if (ko.zones.length === 0 && ko.selfCollision === false) return OK;
  const start = collisions(robot, from, ko, options, true);
  if (start.length === 0) return checkPath(robot, from, to, ko, options);
  const goal = Array.from(from, (p, i) => (Number.isNaN(to[i]!) ? p : to[i]!));
  for (const c of collisions(robot, goal, ko, options, true)) {
    const was = start.find((s) => s.link === c.link && s.other === c.other);
    if (!was || c.depth > was.depth + ZONE_TOLERANCE_MM) return c;
  }
  return OK;
}

/**
 * The first collision on a plan's path (its samples and the straight joint-space path between
 * consecutive ones), with the sample it leads to, or null. A plan starting in a collision is
 * checked at its end only (`checkZonesMove`'s way out).
 */
export function planInZone(
  robot: MotionRobot,
  plan: Plan,
  keepOut?: ProfileKeepOut,
  options: Partial<ZoneOptions> = {},
): { sample: number; check: ZoneHit } | null {
  const ko = keepOutOf(robot, keepOut);
  const samples = plan.samples;
  const last = samples.length - 1;
  if (collisions(robot, samples[0]!.pwm, ko, options, false).length > 0) {
    const c = checkZonesMove(robot, samples[0]!.pwm, samples[last]!.pwm, ko, options);
    return c.ok ? null : { sample: last, check: c };
  }
  for (let i = 1; i <= last; i++) {
    const c = checkPath(robot, samples[i - 1]!.pwm, samples[i]!.pwm, ko, options);
    if (!c.ok) return { sample: i, check: c };
  }
  return null;
}
