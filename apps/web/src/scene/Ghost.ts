/**
 * The translucent ghost arm: the plan preview while there is one (the page's ghost source), else the previewed
 * IK solution of the Cartesian target (refused by a keep-out zone: its offending link red), a
 * refused jog's pose (its offending link red), else the pose this HUD last commanded (store/ghostPose.ts),
 * hidden when that is where the live arm already is or when the Ghost panel turns it off. Posed
 * every frame by the 3D view's loop by mutation: the inputs to `ghostPose` are one object,
 * refilled in place, and the angles one array; nothing is allocated per frame.
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import { ghostPose, type GhostInputs } from '../core/store/ghostPose.ts';
import type { SceneFrame } from './render/SceneFrame.ts';
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

/** The offending link of a refused target (keep-out zone, self-collision): opaque-ish red. */
const hitMaterial = new THREE.MeshStandardMaterial({
  color: 0xef4444,
  emissive: 0x7f1d1d,
  emissiveIntensity: 0.6,
  transparent: true,
  opacity: 0.75,
  depthWrite: false,
  roughness: 0.4,
});

/** What the ghost reads of the runtime's snapshot of the page (read afresh every frame). */
export type GhostFrame = Pick<SceneFrame, 'arm' | 'rendered' | 'commandedPwm' | 'target' | 'plan'>;

export class Ghost {
  /** The URDF joint whose child link is painted red now ('' = none). */
  painted = '';
  /** What the ghost shows now (the runtime reports it; the Ghost panel's legend says it). */
  shows: 'nothing' | 'preview' | 'commanded' | 'plan' | 'refused' = 'nothing';
  private readonly saved = new Map<THREE.Mesh, THREE.Material | THREE.Material[]>();
  private readonly angles: Float64Array;
  /** `ghostPose`'s inputs, refilled each frame (the snapshot's arrays are replaced by messages). */
  private readonly inputs: GhostInputs;

  constructor(
    readonly posed: PosedRobot,
    private readonly frame: GhostFrame,
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
      arm: frame.arm,
      rendered: frame.rendered,
      commandedPwm: frame.commandedPwm,
      previewOk: false,
      previewAngles: frame.target.angles,
    };
  }

  get robot(): URDFRobot {
    return this.posed.robot;
  }

  /**
   * Poses the ghost: the plan preview's pose while there is one, else the target or commanded
   * pose. True when it moved, appeared or disappeared.
   */
  update(): boolean {
    const t = this.frame.target;
    const shows = !t.ghostEnabled
      ? 'nothing'
      : t.refused
        ? this.refusedPose()
        : this.planPose()
          ? 'plan'
          : ghostPose(this.refill(), this.angles);
    this.shows = shows;
    const robot = this.posed.robot;
    const visible = shows !== 'nothing';
    let changed = this.paint(
      shows === 'preview' ? t.hitJoint : shows === 'refused' ? t.refusedJoint : '',
    );
    if (robot.visible !== visible) {
      robot.visible = visible;
      changed = true;
    }
    if (visible && this.posed.pose(this.angles)) changed = true;
    return changed;
  }

  /**
   * Paints the child link of URDF joint `joint` red (a refused target's offending link) and
   * restores the rest; true when that changed anything. Runs only when the joint changes.
   */
  private paint(joint: string): boolean {
    if (joint === this.painted) return false;
    for (const [mesh, material] of this.saved) mesh.material = material;
    this.saved.clear();
    this.painted = joint;
    const link = joint
      ? this.posed.robot.joints[joint]?.children.find(
          (c) => (c as { isURDFLink?: boolean }).isURDFLink,
        )
      : undefined;
    const visit = (o: THREE.Object3D) => {
      if ((o as { isURDFJoint?: boolean }).isURDFJoint) return; // the next link: not this one
      const mesh = o as THREE.Mesh;
      if (mesh.isMesh) {
        this.saved.set(mesh, mesh.material);
        mesh.material = hitMaterial;
      }
      o.children.forEach(visit);
    };
    link?.children.forEach(visit);
    return true;
  }

  /** A refused jog's pose (servos it leaves be where the arm is drawn). */
  private refusedPose(): 'refused' {
    const a = this.frame.target.refusedAngles;
    for (let i = 0; i < this.angles.length; i++)
      this.angles[i] = Number.isNaN(a[i]!) ? (this.frame.rendered[i] ?? 0) : a[i]!;
    return 'refused';
  }

  /** The plan preview's pose, when it shows one. */
  private planPose(): boolean {
    const p = this.frame.plan;
    if (!p) return false;
    for (let i = 0; i < this.angles.length; i++) this.angles[i] = p[i] ?? NaN;
    return true;
  }

  private refill(): GhostInputs {
    const g = this.inputs;
    const s = this.frame;
    const t = s.target;
    g.arm = s.arm;
    g.rendered = s.rendered;
    g.commandedPwm = s.commandedPwm;
    // A target refused by a zone is shown too, its offending link red (`paint`).
    g.previewOk = t.active && (t.code === 0 || t.hitJoint !== '');
    g.previewAngles = t.angles;
    return g;
  }
}
