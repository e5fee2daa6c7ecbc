/**
 * The numeric IK's serial chain (`Chain`, `@armtwin/ik`) from a profile and its URDF: the URDF
 * joints on the path from the profile's base link to its tip link, each moving joint tied to the profile servo that drives it. Fixed joints are
 * folded into the next moving joint's origin (or into the tip offset), so FK does one
 * multiply and one motion per degree of freedom. Lengths in mm; joint values in URDF units
 * (radians for revolute, metres for prismatic); limits are the profile's.
 */
import {
  createMat4,
  mat4FromXyzRpy,
  mat4Identity,
  mat4Multiply,
  type Chain,
  type ChainJoint,
  type Mat4,
} from '@armtwin/ik';
import { jointLimits } from '../profile/convert.ts';
import type { Profile } from '../profile/types.ts';
import type { UrdfJoint } from './urdf.ts';

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
