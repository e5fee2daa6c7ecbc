/**
 * The translucent ghost arm: the plan preview while there is one (`GhostSource`), else the previewed
 * IK solution of the Cartesian target, else the pose this HUD last commanded (store/ghostPose.ts),
 * hidden when that is where the live arm already is or when the Ghost panel turns it off. Posed
 * every frame by the Viewer's loop by mutation: the inputs to `ghostPose` are one object,
 * refilled in place, and the angles one array; nothing is allocated per frame.
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { ArmStore } from '../store/ArmStore.ts';
import type { TargetPreview } from '../store/TargetPreview.ts';
import { ghostPose, type GhostInputs } from '../store/ghostPose.ts';
import type { GhostSource } from '../robots/sceneHooks.ts';
import type { MaterialFactory } from './loadRobot.ts';
import type { PosedRobot } from './PosedRobot.ts';

/**
 * Links whose visuals the ghost leaves out: the fixed pedestal, the turntable and the rail only
 * ever differ from the live arm's by yaw or not at all, so the ghost never flickers inside them.
 */
const HIDDEN_LINKS = ['base_link', 'turret', 'rail'];

/** The ghost's look: one translucent cyan for every part. */
export const ghostMaterial: MaterialFactory = () =>
  new THREE.MeshStandardMaterial({
    color: 0x67e8f9,
    emissive: 0x0e7490,
    emissiveIntensity: 0.4,
    transparent: true,
    opacity: 0.35,
    depthWrite: false,
    // Strictly nearer only: where the ghost coincides with the live arm it is not drawn (no stripes).
    depthFunc: THREE.LessDepth,
    roughness: 0.4,
  });

export class Ghost {
  private readonly angles: Float64Array;
  /** `ghostPose`'s inputs, refilled each frame (the store's arrays are replaced on `configure`). */
  private readonly inputs: GhostInputs;

  constructor(
    readonly posed: PosedRobot,
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
  ) {
    const robot = posed.robot;
    robot.traverse((o) => {
      o.castShadow = false;
      o.renderOrder = 1;
    });
    for (const name of HIDDEN_LINKS) {
      for (const child of robot.links[name]?.children ?? [])
        if ((child as { isURDFVisual?: boolean }).isURDFVisual) child.visible = false;
    }
    robot.visible = false;
    this.angles = new Float64Array(posed.servoCount);
    this.inputs = {
      arm: store.opts.arm,
      rendered: store.rendered,
      commandedPwm: store.commandedPwm,
      previewOk: false,
      previewAngles: target.angles,
    };
  }

  get robot(): URDFRobot {
    return this.posed.robot;
  }

  /**
   * Poses the ghost for `now`: `source`'s sample while it has one (the plan preview), else the
   * target or commanded pose. True when it moved, appeared or disappeared.
   */
  update(now: number, source: GhostSource | null): boolean {
    const t = this.target;
    const shows = !t.ghostEnabled
      ? 'nothing'
      : source?.sample(now, this.angles)
        ? 'plan'
        : ghostPose(this.refill(), this.angles);
    t.ghostShows = shows;
    const robot = this.posed.robot;
    const visible = shows !== 'nothing';
    let changed = false;
    if (robot.visible !== visible) {
      robot.visible = visible;
      changed = true;
    }
    if (visible && this.posed.pose(this.angles)) changed = true;
    return changed;
  }

  private refill(): GhostInputs {
    const g = this.inputs;
    const s = this.store;
    const t = this.target;
    g.arm = s.opts.arm;
    g.rendered = s.rendered;
    g.commandedPwm = s.commandedPwm;
    g.previewOk = t.active && t.code === 0;
    g.previewAngles = t.angles;
    return g;
  }
}
