/**
 * A serial chain for the numeric IK: the moving joints from a base link to a tip link, each tied
 * to the servo that drives it. Lengths in mm; joint values in URDF units (radians for revolute,
 * metres for prismatic). `@armtwin/robot` builds one from a profile and its URDF (`buildChain`,
 * `chainFromUrdf`).
 */
import type { Mat4 } from './mat4.ts';

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
