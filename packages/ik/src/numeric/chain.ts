/**
 * A serial chain for the numeric IK: the URDF joints on the path from the profile's base link
 * to its tip link, each moving joint tied to the profile servo that drives it. Fixed joints are
 * folded into the next moving joint's origin (or into the tip offset), so FK does one
 * multiply and one motion per degree of freedom. Lengths in mm; joint values in URDF units
 * (radians for revolute, metres for prismatic); limits are the profile's.
 */
import { jointLimits } from '../profile/convert.ts';
import type { Profile } from '../profile/types.ts';
import { createMat4, mat4FromXyzRpy, mat4Identity, mat4Multiply, type Mat4 } from './mat4.ts';
import type { UrdfJoint } from './urdf.ts';

export interface ChainJoint {
  /** URDF joint name. */
  readonly name: string;
  readonly type: 'revolute' | 'prismatic';
  /** Transform from the previous moving joint's frame (or the base) to this joint's, mm. */
  readonly origin: Mat4;
  /** Unit axis in this joint's frame. */
  readonly axis: readonly [number, number, number];
  /** Index of the servo in `profile.servos`. */
  readonly servoIndex: number;
}

export interface Chain {
  readonly baseLink: string;
  readonly tipLink: string;
  /** The moving joints, base to tip; the joint vector `q` follows this order. */
  readonly joints: readonly ChainJoint[];
  readonly dof: number;
  /** Joint limits, radians or metres, from the profile. */
  readonly lower: Float64Array;
  readonly upper: Float64Array;
  /** Last moving joint's frame → tip link frame, mm. */
  readonly tip: Mat4;
  /**
   * An upper bound on the distance from the first joint's origin to the tip, mm: every link
   * length after it plus every prismatic joint's travel. Targets farther away are out of reach.
   */
  readonly reachMm: number;
  /** Sum of the link lengths (no prismatic travel), mm: the chain's length scale. */
  readonly lengthMm: number;
}

export type BuildChainResult = { ok: true; chain: Chain } | { ok: false; errors: string[] };

function originMm(j: UrdfJoint): Mat4 {
  const [x, y, z] = j.xyz;
  const [r, p, w] = j.rpy;
  return mat4FromXyzRpy(createMat4(), x * 1000, y * 1000, z * 1000, r, p, w);
}

/** Build the chain from a parsed profile and the URDF's joints (`parseUrdfJoints`). */
export function buildChain(profile: Profile, urdfJoints: readonly UrdfJoint[]): BuildChainResult {
  const { baseLink, tipLink } = profile.ik;
  const byChild = new Map(urdfJoints.map((j) => [j.child, j]));
  const path: UrdfJoint[] = [];
  for (let link = tipLink; link !== baseLink;) {
    const j = byChild.get(link);
    if (!j) {
      const why =
        link === tipLink
          ? `no joint has tip link "${tipLink}" as its child`
          : `link "${baseLink}" is not an ancestor of tip link "${tipLink}"`;
      return { ok: false, errors: [why] };
    }
    path.unshift(j);
    link = j.parent;
    if (path.length > urdfJoints.length)
      return { ok: false, errors: ['the URDF joints form a loop'] };
  }
  const errors: string[] = [];
  const joints: ChainJoint[] = [];
  let pending = mat4Identity(createMat4());
  let lengthMm = 0,
    travelMm = 0;
  for (const j of path) {
    const o = originMm(j);
    if (joints.length > 0) lengthMm += Math.hypot(o[12]!, o[13]!, o[14]!);
    mat4Multiply(pending, pending, o);
    if (j.type === 'fixed') continue;
    const servoIndex = profile.servos.findIndex((s) => s.joint === j.name);
    const servo = profile.servos[servoIndex];
    const type = j.type === 'prismatic' ? 'prismatic' : 'revolute';
    if (j.type === 'floating' || j.type === 'planar')
      errors.push(
        `joint "${j.name}" is ${j.type}; only revolute, continuous, prismatic and fixed joints can be in a chain`,
      );
    else if (j.mimic !== undefined)
      errors.push(`joint "${j.name}" mimics "${j.mimic}"; mimic joints cannot be in a chain`);
    else if (!servo)
      errors.push(
        `joint "${j.name}" is on the chain from "${baseLink}" to "${tipLink}" but no servo in the profile drives it`,
      );
    else if (servo.type !== type)
      errors.push(
        `joint "${j.name}" is ${j.type} in the URDF but servo ${servo.key} is ${servo.type}`,
      );
    else {
      const n = Math.hypot(...j.axis);
      if (type === 'prismatic') travelMm += servo.max - servo.min;
      joints.push({
        name: j.name,
        type,
        origin: pending,
        axis: [j.axis[0] / n, j.axis[1] / n, j.axis[2] / n],
        servoIndex,
      });
    }
    pending = mat4Identity(createMat4());
  }
  if (joints.length === 0 && errors.length === 0)
    errors.push(`no moving joint between "${baseLink}" and "${tipLink}"`);
  if (errors.length > 0) return { ok: false, errors };
  const lower = new Float64Array(joints.length);
  const upper = new Float64Array(joints.length);
  joints.forEach((j, i) => {
    const lim = jointLimits(profile.servos[j.servoIndex]!);
    lower[i] = lim.min;
    upper[i] = lim.max;
  });
  const chain: Chain = {
    baseLink,
    tipLink,
    joints,
    dof: joints.length,
    lower,
    upper,
    tip: pending,
    reachMm: lengthMm + travelMm,
    lengthMm,
  };
  return { ok: true, chain };
}
