/**
 * A `profile.json` derived from a URDF alone (`armtwin robot import`). The rules, documented in
 * docs/robots.md ("Import your robot"):
 * - the chain runs from the root link to the tool-centre link: a link named like a tool centre
 *   (`tcp`, `tool0`, `flange`, `ee_link`, `end_effector`, …; the deepest such), else a tool
 *   frame (a fixed link named like `gripper_frame_link`, tool-rules.ts), else the new `tcp` link
 *   (fixed, at the frame of the deepest link: most movable joints from the root, then most
 *   joints, then first written) added to the URDF, where the TCP offset can be set; links moved
 *   by a tool joint (a jaw or finger at the end of a chain, tool-rules.ts) are never the tip;
 * - servos: the chain's movable joints in order from the root, then every other movable joint
 *   that is not a mimic (gripper fingers, tool joints), ids from the URDF's numbered
 *   `<transmission>` actuators when each has one, else 000, 001, … in that order;
 * - mimic joints are not servos: urdf-loader moves them with their leader; they are listed in
 *   the profile's `$import.mimic`;
 * - limits: revolute radians → degrees, prismatic metres → millimetres (rounded inwards to 0.01);
 *   a continuous joint gets ±180° (every orientation once);
 * - a revolute joint with more than 270° of travel (continuous ones included) gets
 *   `"units": "angle"` (angle frames), since pulses carry only 270°; otherwise pulses, with
 *   offset 0 when the range fits ±135° of servo angle and the range's centre otherwise;
 * - speed: the URDF's `velocity` (rad/s → °/s, m/s → mm/s), or 90 °/s / 100 mm/s when absent;
 * - `home`: every joint at 0 (or its nearest limit);
 * - polarity +1 and the offsets are left for calibration, as is the bus.
 */
import { parseProfile } from '../profile/parse.ts';
import { chainFromUrdf } from '../urdf/chain-from-urdf.ts';
import { parseUrdfJoints, type UrdfJoint } from '../urdf/urdf.ts';
import {
  TOOL_FRAME_NAMES,
  isToolFrame,
  linksBeyond,
  toolJoints,
  transmissionIds,
} from './tool-rules.ts';

/** A profile name: a folder name. */
export const IMPORT_NAME = /^[a-z0-9_-]{1,32}$/;
/** Revolute travel a pulse servo carries (PROTOCOL §2), degrees. */
export const PULSE_TRAVEL_DEG = 270;
/** Range given to a continuous joint, degrees either side of 0. */
export const CONTINUOUS_RANGE_DEG = 180;
/** Speeds used when the URDF gives none: °/s (revolute) and mm/s (prismatic). */
export const DEFAULT_SPEEDS = { revolute: 90, prismatic: 100 } as const;
/** Link names taken for the tool centre, best first. */
export const TCP_NAMES: readonly RegExp[] = [
  /(^|[_-])tcp$/i,
  /(^|[_-])tool_?centre|tool_?center/i,
  /(^|[_-])tool0$/i,
  /(^|[_-])flange$/i,
  /(^|[_-])(ee|eef)(_link)?$/i,
  /end_?effector/i,
];

export interface DerivedProfile {
  /** The profile.json object (with an `$import` record of what was decided). */
  json: Record<string, unknown>;
  /** Decisions a user should know about (tool centre chosen, continuous joints, …). */
  notes: string[];
  /** The URDF to write: the input, with a `tcp` link added when none was named like one. */
  urdf: string;
}

export type DeriveProfileResult =
  { ok: true; derived: DerivedProfile } | { ok: false; errors: string[] };

const round2 = (x: number) => Math.round(x * 100) / 100;
/** Limits rounded inwards to 0.01, so the profile never allows more than the URDF. */
const inwards = (lo: number, hi: number) => [
  Math.ceil(lo * 100 - 1e-6) / 100 + 0,
  Math.floor(hi * 100 + 1e-6) / 100 + 0,
];
const movable = (j: UrdfJoint) =>
  j.type === 'revolute' || j.type === 'continuous' || j.type === 'prismatic';

/** A profile name from any robot name: lower case, `[a-z0-9_-]`, at most 32 characters. */
export function profileNameFrom(text: string): string {
  const n = text
    .toLowerCase()
    .replace(/[^a-z0-9_-]+/g, '_')
    .replace(/^_+|_+$/g, '')
    .slice(0, 32);
  return n || 'robot';
}

/** Derives the profile of the URDF `urdf`, to be written as `<name>/<urdfFile>`. */
export function deriveProfile(urdf: string, name: string, urdfFile: string): DeriveProfileResult {
  if (!IMPORT_NAME.test(name))
    return { ok: false, errors: [`name "${name}" must be [a-z0-9_-]{1,32} (a folder name)`] };
  const parsed = parseUrdfJoints(urdf);
  if (!parsed.ok) return { ok: false, errors: parsed.errors.map((e) => `URDF: ${e}`) };
  const { joints, links } = parsed;
  const byChild = new Map(joints.map((j) => [j.child, j]));
  const roots = links.filter((l) => !byChild.has(l) && joints.some((j) => j.parent === l));
  if (!joints.some((j) => movable(j) && j.mimic === undefined))
    return {
      ok: false,
      errors: [
        'the URDF has no movable joint (revolute, continuous or prismatic) that is not a mimic',
      ],
    };
  if (roots.length !== 1)
    return {
      ok: false,
      errors: [
        `the URDF must have one root link, found ${roots.length ? roots.join(', ') : 'none'}`,
      ],
    };
  const root = roots[0]!;
  const pathTo = (link: string): UrdfJoint[] => {
    const path: UrdfJoint[] = [];
    for (let l = link; l !== root;) {
      const j = byChild.get(l);
      if (!j || path.length > joints.length) return [];
      path.unshift(j);
      l = j.parent;
    }
    return path;
  };
  const depth = (link: string) => {
    const p = pathTo(link);
    return { moving: p.filter((j) => movable(j) && j.mimic === undefined).length, all: p.length };
  };
  const deeper = (a: string, b: string) => {
    const da = depth(a),
      db = depth(b);
    return da.moving !== db.moving ? da.moving > db.moving : da.all > db.all;
  };
  const tools = toolJoints(joints);
  const onTool = linksBeyond(tools, joints);
  const all = links.filter((l) => l === root || pathTo(l).length > 0);
  // Links moved by a jaw or finger are never the tool centre (unless nothing else moves).
  const offTool = all.filter((l) => !onTool.has(l));
  const reachable = offTool.some((l) => depth(l).moving > 0) ? offTool : all;
  let tip = reachable.reduce((best, l) => (deeper(l, best) ? l : best), root);
  let tipWhy = `the deepest link (no link is named like a tool centre)`;
  const rules = [
    ...TCP_NAMES.map((re) => ({ re, ok: (l: string) => re.test(l), what: 'a tool centre' })),
    ...TOOL_FRAME_NAMES.map((re) => ({
      re,
      ok: (l: string) => isToolFrame(l, joints, re),
      what: 'a tool frame, on a fixed joint',
    })),
  ];
  for (const { re, ok, what } of rules) {
    const named = reachable.filter((l) => ok(l) && depth(l).moving > 0);
    if (named.length === 0) continue;
    tip = named.reduce((best, l) => (deeper(l, best) ? l : best));
    tipWhy = `named like ${what} (${re.source})`;
    break;
  }
  const chain = pathTo(tip);
  let out = urdf;
  if (tipWhy.startsWith('the deepest')) {
    // A tool-centre link of its own at the deepest link's frame: the place to set the TCP offset.
    const taken = new Set([...links, ...joints.map((j) => j.name)]);
    let k = 0;
    while (taken.has(k ? `tcp${k}` : 'tcp') || taken.has(k ? `tcp${k}_joint` : 'tcp_joint')) k++;
    const tcp = k ? `tcp${k}` : 'tcp';
    out = urdf.replace(
      /<\/robot>\s*$/,
      `  <!-- added by armtwin robot import: the tool centre (set its origin to the tool's tip) -->\n` +
        `  <link name="${tcp}"/>\n  <joint name="${tcp}_joint" type="fixed">\n` +
        `    <parent link="${tip}"/>\n    <child link="${tcp}"/>\n    <origin xyz="0 0 0" rpy="0 0 0"/>\n  </joint>\n</robot>\n`,
    );
    if (out !== urdf) {
      tipWhy = `added at the deepest link "${tip}" (no link is named like a tool centre)`;
      tip = tcp;
    }
  }
  const errors: string[] = [];
  for (const j of chain) {
    if (j.type === 'floating' || j.type === 'planar')
      errors.push(
        `joint "${j.name}" on the chain ${root} → ${tip} is ${j.type}: armtwin drives revolute, continuous and prismatic joints`,
      );
    if (movable(j) && j.mimic !== undefined)
      errors.push(
        `joint "${j.name}" on the chain ${root} → ${tip} mimics "${j.mimic}": a chain joint must be driven by its own servo`,
      );
  }
  if (errors.length) return { ok: false, errors };
  const others = joints.filter((j) => movable(j) && j.mimic === undefined && !chain.includes(j));
  const driven = [...chain.filter((j) => movable(j) && j.mimic === undefined), ...others];
  const notes: string[] = [`tool centre: link "${tip}", ${tipWhy}; chain ${root} → ${tip}`];
  const outside = tools.filter((j) => others.includes(j));
  if (outside.length)
    notes.push(
      `tool joints (jogged, left alone by Cartesian moves): ${outside.map((j) => j.name).join(', ')}`,
    );
  const ids = transmissionIds(
    urdf,
    driven.map((j) => j.name),
  );
  if (ids) notes.push(`servo ids from the URDF's <transmission> actuators: ${ids.join(', ')}`);
  const servos: Record<string, unknown>[] = [];
  const home: Record<string, number> = {};
  driven.forEach((j, i) => {
    const key = String(ids ? ids[i]! : i).padStart(3, '0');
    const servo = servoFor(j, key, notes);
    if (typeof servo === 'string') errors.push(servo);
    else {
      servos.push(servo);
      home[key] = Math.min(Math.max(0, servo.min as number), servo.max as number);
    }
  });
  if (others.length)
    notes.push(
      `servos beyond the chain (not used by the IK): ${others.map((j) => j.name).join(', ')}`,
    );
  const mimic = joints
    .filter((j) => j.mimic !== undefined)
    .map((j) => ({ joint: j.name, follows: j.mimic! }));
  if (mimic.length)
    notes.push(
      `mimic joints follow their leader, no servo: ${mimic.map((m) => `${m.joint} ← ${m.follows}`).join(', ')}`,
    );
  if (errors.length) return { ok: false, errors };
  const json: Record<string, unknown> = {
    $import: {
      tcp: { link: tip, why: tipWhy },
      toolJoints: outside.map((j) => j.name),
      mimic,
      calibration: 'bus, polarity and offsets are not in a URDF: calibrate them',
    },
    format: 'armtwin-profile/1',
    name,
    title: parsed.robot || name,
    urdf: urdfFile,
    ik: { kind: 'numeric', baseLink: root, tipLink: tip },
    servos,
    poses: { home: { unit: 'joint', servos: home } },
  };
  const check = parseProfile(json);
  if (!check.ok) return { ok: false, errors: check.errors.map((e) => `derived profile: ${e}`) };
  const built = chainFromUrdf(check.profile, out);
  if (!built.ok) return { ok: false, errors: built.errors.map((e) => `chain: ${e}`) };
  return { ok: true, derived: { json, notes, urdf: out } };
}

function servoFor(j: UrdfJoint, key: string, notes: string[]): Record<string, unknown> | string {
  const prismatic = j.type === 'prismatic';
  const scale = prismatic ? 1000 : 180 / Math.PI;
  let min: number, max: number;
  if (j.type === 'continuous') {
    [min, max] = [-CONTINUOUS_RANGE_DEG, CONTINUOUS_RANGE_DEG];
    notes.push(`${j.name}: continuous, given ±${CONTINUOUS_RANGE_DEG}° on angle frames`);
  } else {
    if (
      j.lower === undefined ||
      j.upper === undefined ||
      !Number.isFinite(j.lower) ||
      !Number.isFinite(j.upper)
    )
      return `joint "${j.name}" (${j.type}) has no <limit lower upper>`;
    [min, max] = inwards(j.lower * scale, j.upper * scale) as [number, number];
    if (!(min < max)) return `joint "${j.name}" has an empty range ${j.lower}…${j.upper}`;
  }
  const speed = j.velocity !== undefined && j.velocity > 0 ? round2(j.velocity * scale) : 0;
  if (!speed)
    notes.push(
      `${j.name}: no velocity limit in the URDF, ${DEFAULT_SPEEDS[prismatic ? 'prismatic' : 'revolute']} used`,
    );
  const servo: Record<string, unknown> = {
    id: key,
    name: j.name,
    joint: j.name,
    type: prismatic ? 'prismatic' : 'revolute',
  };
  if (!prismatic && max - min > PULSE_TRAVEL_DEG) {
    servo.units = 'angle';
    if (j.type !== 'continuous')
      notes.push(`${j.name}: ${round2(max - min)}° of travel, on angle frames`);
  } else if (!prismatic && (min < -PULSE_TRAVEL_DEG / 2 || max > PULSE_TRAVEL_DEG / 2)) {
    servo.offset = round2((min + max) / 2);
    notes.push(`${j.name}: offset ${servo.offset as number}° centres its range on the servo`);
  }
  servo.min = min;
  servo.max = max;
  servo.maxSpeed = speed || DEFAULT_SPEEDS[prismatic ? 'prismatic' : 'revolute'];
  return servo;
}
