/**
 * The replay's "sibling": a third, translucent amber arm standing beside the live one
 * (`SIBLING_OFFSET_M`) that follows the record. Driven from the Viewer's one frame loop: `update(now)`
 * asks the ReplayPlayer for the pose and sets the joints by mutation; it returns true when
 * something must be redrawn. No allocation per frame.
 */
import * as THREE from 'three';
import type { URDFJoint, URDFRobot } from 'urdf-loader';
import { SERVO_JOINTS, jointValueFromAngle } from '../model/armModel.ts';
import type { MaterialFactory } from '../scene/loadRobot.ts';
import type { ReplayPlayer } from './ReplayPlayer.ts';

/**
 * Where the sibling stands relative to the live arm, in the arm's frame, metres: half a metre
 * behind it (−x), outside its 0.35 m reach, which from the default camera is beside it, to the
 * left and above the History panel, clear of the HUD's columns.
 */
export const SIBLING_OFFSET_M = { x: -0.5, y: 0.15 } as const;

/** The sibling's look: translucent amber, so it is told apart from the cyan ghost. */
export const siblingMaterial: MaterialFactory = () =>
  new THREE.MeshStandardMaterial({
    color: 0xfbbf24,
    emissive: 0x92400e,
    emissiveIntensity: 0.35,
    transparent: true,
    opacity: 0.45,
    depthWrite: false,
    roughness: 0.45,
  });

export class ReplaySibling {
  private readonly joints: (URDFJoint | undefined)[];

  constructor(
    readonly robot: URDFRobot,
    private readonly player: ReplayPlayer,
  ) {
    robot.position.set(SIBLING_OFFSET_M.x, SIBLING_OFFSET_M.y, 0);
    robot.visible = false;
    robot.name = 'replay sibling';
    robot.traverse((o) => {
      o.castShadow = false;
      o.renderOrder = 2;
    });
    this.joints = SERVO_JOINTS.map((n) => robot.joints[n]);
  }

  /** True when the sibling moved, appeared or disappeared. */
  update(now: number): boolean {
    let changed = this.player.update(now);
    const visible = this.player.active && this.player.record !== null;
    if (this.robot.visible !== visible) {
      this.robot.visible = visible;
      changed = true;
    }
    if (!visible || !changed) return changed;
    const a = this.player.angles;
    for (let i = 0; i < this.joints.length; i++) {
      const v = a[i] ?? NaN;
      if (!Number.isNaN(v)) this.joints[i]?.setJointValue(jointValueFromAngle(v));
    }
    return true;
  }
}
