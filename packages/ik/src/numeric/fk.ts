/**
 * Forward kinematics of a `Chain`: the tip's 4×4 transform in the base frame (column-major, mm),
 * and, for the Jacobian, each moving joint's world axis and origin. Allocation-free given the
 * outputs (`createFkFrames`).
 */
import {
  createMat4,
  mat4Copy,
  mat4Identity,
  mat4Multiply,
  mat4RotateAxisInPlace,
  mat4TranslateAxisInPlace,
  type Mat4,
} from './mat4.ts';
import type { Chain } from './chain-types.ts';

/** Per-joint world data filled by `chainFkFrames`. */
export interface FkFrames {
  /** Tip transform, base frame, mm. */
  readonly tip: Mat4;
  /** Joint i's world axis at [3i, 3i+3). */
  readonly axes: Float64Array;
  /** Joint i's world origin at [3i, 3i+3), mm. */
  readonly points: Float64Array;
}

export function createFkFrames(chain: Chain): FkFrames {
  return {
    tip: createMat4(),
    axes: new Float64Array(3 * chain.dof),
    points: new Float64Array(3 * chain.dof),
  };
}

/**
 * Tip transform and every moving joint's world axis and origin for joint values `q` (radians
 * or metres, chain order).
 */
export function chainFkFrames(chain: Chain, q: ArrayLike<number>, out: FkFrames): FkFrames {
  const t = mat4Identity(out.tip);
  const { axes, points } = out;
  const joints = chain.joints;
  for (let i = 0; i < joints.length; i++) {
    const j = joints[i]!;
    mat4Multiply(t, t, j.origin);
    const [ax, ay, az] = j.axis;
    const k = 3 * i;
    axes[k] = t[0]! * ax + t[4]! * ay + t[8]! * az;
    axes[k + 1] = t[1]! * ax + t[5]! * ay + t[9]! * az;
    axes[k + 2] = t[2]! * ax + t[6]! * ay + t[10]! * az;
    points[k] = t[12]!;
    points[k + 1] = t[13]!;
    points[k + 2] = t[14]!;
    const v = q[i]!;
    if (j.type === 'revolute') mat4RotateAxisInPlace(t, ax, ay, az, v);
    else mat4TranslateAxisInPlace(t, ax, ay, az, v * 1000);
  }
  mat4Multiply(t, t, chain.tip);
  return out;
}

const scratch = new Map<Chain, FkFrames>();

/**
 * The tip's transform (column-major 4×4, base frame, translation in mm) for joint values `q`
 * (radians or metres, chain order), into `out`.
 */
export function chainFk(chain: Chain, q: ArrayLike<number>, out: Mat4 = createMat4()): Mat4 {
  let frames = scratch.get(chain);
  if (frames === undefined) {
    if (scratch.size > 16) scratch.clear();
    frames = createFkFrames(chain);
    scratch.set(chain, frames);
  }
  return mat4Copy(out, chainFkFrames(chain, q, frames).tip);
}
