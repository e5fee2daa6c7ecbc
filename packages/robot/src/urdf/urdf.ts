/**
 * A pure URDF reader: the `<robot>`'s own `<joint>` children (name, type, parent, child, origin
 * xyz/rpy, axis, limit, mimic) and link names, read with an XML parser (./urdf-xml.ts), so the
 * `<joint>` references inside `<ros2_control>`, `<transmission>` and `<gazebo>` blocks (and
 * comments) are never taken for joints. Enough for the kinematic chain; visuals, inertia and
 * collisions are ignored. Its output is plain JSON, so a chain can also be given pre-extracted.
 */
import { attribute, childElement, childElements, parseUrdfXml } from './urdf-xml.ts';

export type UrdfJointType =
  'revolute' | 'continuous' | 'prismatic' | 'fixed' | 'floating' | 'planar';

export interface UrdfJoint {
  name: string;
  type: UrdfJointType;
  parent: string;
  child: string;
  /** `<origin xyz>`, metres (default 0 0 0). */
  xyz: [number, number, number];
  /** `<origin rpy>`, radians (default 0 0 0). */
  rpy: [number, number, number];
  /** `<axis xyz>`, as written (default 1 0 0, URDF's). */
  axis: [number, number, number];
  /** `<limit lower upper velocity>` when present (radians or metres, per second). */
  lower?: number;
  upper?: number;
  velocity?: number;
  /** The joint this one mimics, when it has `<mimic>`. */
  mimic?: string;
}

export type ParseUrdfResult =
  | { ok: true; robot: string; links: string[]; joints: UrdfJoint[] }
  | { ok: false; errors: string[] };

const TYPES: readonly string[] = [
  'revolute',
  'continuous',
  'prismatic',
  'fixed',
  'floating',
  'planar',
];

function vec3(
  text: string | undefined,
  fallback: [number, number, number],
): [number, number, number] | undefined {
  if (text === undefined) return [...fallback];
  const parts = text.trim().split(/\s+/).map(Number);
  return parts.length === 3 && parts.every(Number.isFinite)
    ? (parts as [number, number, number])
    : undefined;
}

function optNumber(text: string | undefined): number | undefined {
  if (text === undefined) return undefined;
  const n = Number(text);
  return text.trim() !== '' && Number.isFinite(n) ? n : NaN;
}

/** Parse the joints and links of a URDF document. Never throws. */
export function parseUrdfJoints(xml: string): ParseUrdfResult {
  const errors: string[] = [];
  const parsed = parseUrdfXml(xml);
  if (!parsed.ok) return parsed;
  const robotName = attribute(parsed.robot, 'name') ?? '';
  const links = childElements(parsed.robot, 'link').map((l) => attribute(l, 'name') ?? '');
  const joints: UrdfJoint[] = [];
  for (const el of childElements(parsed.robot, 'joint')) {
    const a = { name: attribute(el, 'name'), type: attribute(el, 'type') };
    const child = (tag: string, attr: string) => attribute(childElement(el, tag), attr);
    const where = `joint "${a.name ?? '?'}"`;
    const parent = child('parent', 'link');
    const kid = child('child', 'link');
    const xyz = vec3(child('origin', 'xyz'), [0, 0, 0]);
    const rpy = vec3(child('origin', 'rpy'), [0, 0, 0]);
    const axis = vec3(child('axis', 'xyz'), [1, 0, 0]);
    const bad = [
      !a.name && 'has no name',
      !TYPES.includes(a.type ?? '') &&
        `has type ${JSON.stringify(a.type)}, not one of ${TYPES.join(', ')}`,
      !parent && 'has no <parent link>',
      !kid && 'has no <child link>',
      !xyz && '<origin xyz> is not 3 numbers',
      !rpy && '<origin rpy> is not 3 numbers',
      !axis && '<axis xyz> is not 3 numbers',
      axis && Math.hypot(...axis) === 0 && a.type !== 'fixed' && '<axis xyz> is zero',
    ].filter((e): e is string => typeof e === 'string');
    for (const e of bad) errors.push(`${where} ${e}`);
    if (bad.length > 0) continue;
    const j: UrdfJoint = {
      name: a.name!,
      type: a.type as UrdfJointType,
      parent: parent!,
      child: kid!,
      xyz: xyz!,
      rpy: rpy!,
      axis: axis!,
    };
    const lower = optNumber(child('limit', 'lower')),
      upper = optNumber(child('limit', 'upper')),
      velocity = optNumber(child('limit', 'velocity'));
    if (Number.isNaN(lower) || Number.isNaN(upper) || Number.isNaN(velocity))
      errors.push(`${where} <limit> has a value that is not a number`);
    if (lower !== undefined) j.lower = lower;
    if (upper !== undefined) j.upper = upper;
    if (velocity !== undefined) j.velocity = velocity;
    const mimic = child('mimic', 'joint');
    if (mimic !== undefined) j.mimic = mimic;
    joints.push(j);
  }
  if (joints.length === 0 && errors.length === 0) errors.push('no <joint> elements');
  return errors.length > 0 ? { ok: false, errors } : { ok: true, robot: robotName, links, joints };
}
