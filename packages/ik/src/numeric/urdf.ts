/**
 * A tiny, pure URDF reader: the `<joint>` elements (name, type, parent, child, origin xyz/rpy,
 * axis, limit, mimic) and the link names, from the XML text. No DOM: comments and
 * `<transmission>` blocks (whose `<joint>` children are references, not joints) are removed,
 * then elements are matched by pattern. Enough for the kinematic chain; visuals, inertia and
 * collisions are ignored. Its output is plain JSON, so a chain can also be given pre-extracted.
 */

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

function attrs(text: string): Record<string, string> {
  const out: Record<string, string> = {};
  for (const m of text.matchAll(/([A-Za-z_:][\w:.-]*)\s*=\s*(?:"([^"]*)"|'([^']*)')/g))
    out[m[1]!] = m[2] ?? m[3] ?? '';
  return out;
}

/** The attributes of the first `<tag …>` in `body`, or undefined. */
function child(body: string, tag: string): Record<string, string> | undefined {
  const m = new RegExp(`<${tag}\\b([^>]*?)/?>`).exec(body);
  return m ? attrs(m[1]!) : undefined;
}

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
  const text = xml
    .replace(/<!--[\s\S]*?-->/g, '')
    .replace(/<transmission\b[\s\S]*?<\/transmission>/g, '');
  const robot = /<robot\b([^>]*)>/.exec(text);
  if (!robot) return { ok: false, errors: ['no <robot> element'] };
  const robotName = attrs(robot[1]!).name ?? '';
  const links = [...text.matchAll(/<link\b([^>]*?)\/?>/g)].map((m) => attrs(m[1]!).name ?? '');
  const joints: UrdfJoint[] = [];
  for (const m of text.matchAll(/<joint\b([^>]*?)(?:\/>|>([\s\S]*?)<\/joint>)/g)) {
    const a = attrs(m[1]!);
    const body = m[2] ?? '';
    const where = `joint "${a.name ?? '?'}"`;
    const parent = child(body, 'parent')?.link;
    const kid = child(body, 'child')?.link;
    const origin = child(body, 'origin') ?? {};
    const limit = child(body, 'limit') ?? {};
    const xyz = vec3(origin.xyz, [0, 0, 0]);
    const rpy = vec3(origin.rpy, [0, 0, 0]);
    const axis = vec3(child(body, 'axis')?.xyz, [1, 0, 0]);
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
    const lower = optNumber(limit.lower),
      upper = optNumber(limit.upper),
      velocity = optNumber(limit.velocity);
    if (Number.isNaN(lower) || Number.isNaN(upper) || Number.isNaN(velocity))
      errors.push(`${where} <limit> has a value that is not a number`);
    if (lower !== undefined) j.lower = lower;
    if (upper !== undefined) j.upper = upper;
    if (velocity !== undefined) j.velocity = velocity;
    const mimic = child(body, 'mimic')?.joint;
    if (mimic !== undefined) j.mimic = mimic;
    joints.push(j);
  }
  if (joints.length === 0 && errors.length === 0) errors.push('no <joint> elements');
  return errors.length > 0 ? { ok: false, errors } : { ok: true, robot: robotName, links, joints };
}
