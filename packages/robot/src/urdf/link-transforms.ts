/**
 * Every URDF joint's transform from its parent link to its child link at given joint values
 * (Foxglove's `FrameTransform`), so a robot tool draws the arm where it is: what the MCAP export
 * writes for a recording and the live Foxglove server sends for each report. URDF joints without
 * a value stay at 0, a mimic joint takes its master's value. Uses @armtwin/ik's URDF math. Pure.
 */
import {
  createMat4,
  mat4FromXyzRpy,
  mat4RotateAxisInPlace,
  mat4TranslateAxisInPlace,
  type Mat4,
} from '@armtwin/ik';
import type { UrdfJoint } from './urdf.ts';

export interface LinkTransform {
  parent: string;
  child: string;
  translation: [number, number, number];
  /** Unit quaternion x, y, z, w. */
  rotation: [number, number, number, number];
}

/** Rotation of a rigid transform as a unit quaternion (x, y, z, w). */
function quaternionOf(m: Mat4): [number, number, number, number] {
  const [m00, m10, m20, , m01, m11, m21, , m02, m12, m22] = m as unknown as number[];
  const trace = m00! + m11! + m22!;
  let x: number, y: number, z: number, w: number;
  if (trace > 0) {
    const s = 0.5 / Math.sqrt(trace + 1);
    w = 0.25 / s;
    x = (m21! - m12!) * s;
    y = (m02! - m20!) * s;
    z = (m10! - m01!) * s;
  } else if (m00! > m11! && m00! > m22!) {
    const s = 2 * Math.sqrt(1 + m00! - m11! - m22!);
    w = (m21! - m12!) / s;
    x = 0.25 * s;
    y = (m01! + m10!) / s;
    z = (m02! + m20!) / s;
  } else if (m11! > m22!) {
    const s = 2 * Math.sqrt(1 + m11! - m00! - m22!);
    w = (m02! - m20!) / s;
    x = (m01! + m10!) / s;
    y = 0.25 * s;
    z = (m12! + m21!) / s;
  } else {
    const s = 2 * Math.sqrt(1 + m22! - m00! - m11!);
    w = (m10! - m01!) / s;
    x = (m02! + m20!) / s;
    y = (m12! + m21!) / s;
    z = 0.25 * s;
  }
  const n = Math.hypot(x, y, z, w);
  return [x / n, y / n, z / n, w / n];
}

/** Every URDF joint's parent → child transform at `values` (joint name → rad or m). */
export function linkTransforms(
  joints: readonly UrdfJoint[],
  values: ReadonlyMap<string, number>,
): LinkTransform[] {
  const m = createMat4();
  return joints.map((j) => {
    const q = values.get(j.mimic ?? j.name) ?? values.get(j.name) ?? 0;
    mat4FromXyzRpy(m, ...j.xyz, ...j.rpy);
    const [ax, ay, az] = j.axis;
    const n = Math.hypot(ax, ay, az) || 1;
    if (j.type === 'revolute' || j.type === 'continuous')
      mat4RotateAxisInPlace(m, ax / n, ay / n, az / n, Number.isFinite(q) ? q : 0);
    else if (j.type === 'prismatic')
      mat4TranslateAxisInPlace(m, ax / n, ay / n, az / n, Number.isFinite(q) ? q : 0);
    return {
      parent: j.parent,
      child: j.child,
      translation: [m[12]!, m[13]!, m[14]!],
      rotation: quaternionOf(m),
    };
  });
}
