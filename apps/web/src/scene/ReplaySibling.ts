/**
 * The replay's "sibling": a third, translucent amber copy of the active robot standing beside
 * the live one (`SIBLING_OFFSET_M`) that follows the record. It poses through the same joint map
 * as the live arm and the ghost (./PosedRobot.ts), so any robot's record replays. Driven
 * from the 3D view's one frame loop: `update()` reads the pose the page last sent
 * (`SceneFrame.sibling`, ./render/SceneFrame.ts) and sets the joints by mutation; it returns true
 * when something must be redrawn. No allocation per frame.
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { MaterialFactory } from './loadRobot.ts';
import type { PosedRobot } from './PosedRobot.ts';
import type { SceneFrame } from './render/SceneFrame.ts';

/**
 * Where the sibling stands relative to the live arm, in the arm's frame, metres: half a metre
 * behind it (−x), outside the 5-axis arm's 0.35 m reach, which from the default camera is beside
 * it, to the left and above the History panel, clear of the HUD's columns.
 */
export const SIBLING_OFFSET_M = { x: -0.5, y: 0.15 } as const;
/** A robot longer than that (track6's 4 m rail) gets its sibling this far behind its length, m. */
export const SIBLING_GAP_M = 0.3;

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
  /** The pose posed last (each message brings a new array). */
  private shown: Float64Array | null = null;

  constructor(
    readonly posed: PosedRobot,
    private readonly frame: Pick<SceneFrame, 'sibling'>,
  ) {
    const robot = posed.robot;
    robot.position.set(SIBLING_OFFSET_M.x, SIBLING_OFFSET_M.y, 0);
    robot.visible = false;
    robot.name = 'replay sibling';
    robot.traverse((o) => {
      o.castShadow = false;
      o.renderOrder = 2;
    });
  }

  get robot(): URDFRobot {
    return this.posed.robot;
  }

  /**
   * Stands the sibling clear of `live` (in the scene, at its zero pose): `SIBLING_OFFSET_M`
   * behind a robot as small as the 5-axis arm, else behind the robot's whole length along x
   * plus `SIBLING_GAP_M`, so the two never stand inside each other. Once per load.
   */
  standClearOf(live: THREE.Object3D): void {
    live.updateMatrixWorld(true);
    const box = new THREE.Box3().setFromObject(live); // world x is the arm's x
    const length = box.isEmpty() ? 0 : box.max.x - box.min.x;
    const x = Math.min(SIBLING_OFFSET_M.x, -(length + SIBLING_GAP_M));
    this.posed.robot.position.set(x, SIBLING_OFFSET_M.y, 0);
  }

  /** True when the sibling moved, appeared or disappeared. */
  update(): boolean {
    const pose = this.frame.sibling;
    let changed = pose !== this.shown;
    this.shown = pose;
    const robot = this.posed.robot;
    const visible = pose !== null;
    if (robot.visible !== visible) {
      robot.visible = visible;
      changed = true;
    }
    if (!visible || !changed) return changed;
    this.posed.pose(pose);
    return true;
  }
}
