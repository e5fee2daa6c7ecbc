/**
 * A URDF robot posed through the active robot's joint map (`JointMap`, robots/robotSpec.ts):
 * servo i's store angle (degrees) → its URDF joint's value, `scale[i]·angle + bias[i]` (radians,
 * or metres for a prismatic joint). The live arm, the ghost and the replay's sibling each pose
 * through one, built from the same map, so any robot a profile describes moves the same way in
 * all three. `pose` runs every frame: no allocation.
 *
 * Every joint is drawn where it is put, past its URDF limits: the twin shows what the arm
 * reports (a ±360° bus servo whose URDF says ±135°, PROTOCOL.md §8), and limits are checked
 * where commands are made and again at the controller, not by hiding a pose in the drawing.
 */
import type { URDFJoint, URDFRobot } from 'urdf-loader';
import type { JointMap } from '../core/robots/robotSpec.ts';

export class PosedRobot {
  /** Servo i's URDF joint (undefined if the URDF has no joint of that name). */
  private readonly joints: (URDFJoint | undefined)[];

  constructor(
    readonly robot: URDFRobot,
    private readonly map: JointMap,
  ) {
    this.joints = map.names.map((n) => robot.joints[n]);
    // urdf-loader clamps revolute and prismatic joints to their limits unless told not to;
    // mimic joints follow through `setJointValue`, so they are freed as well.
    for (const joint of Object.values(robot.joints)) joint.ignoreLimits = true;
  }

  /** Servos this robot is posed by (the profile's). */
  get servoCount(): number {
    return this.joints.length;
  }

  /** Sets the joints to store angles (degrees; NaN leaves a joint as it is); true if any moved. */
  pose(angles: ArrayLike<number>): boolean {
    const { scale, bias } = this.map;
    let changed = false;
    for (let i = 0; i < this.joints.length; i++) {
      const a = angles[i] ?? NaN;
      if (!Number.isNaN(a) && this.joints[i]?.setJointValue(scale[i]! * a + bias[i]!))
        changed = true;
    }
    return changed;
  }

  /** The URDF joint values drawn now, servo order (NaN for a joint the URDF lacks). */
  values(): number[] {
    return this.joints.map((j) => (j ? j.angle : NaN));
  }
}
