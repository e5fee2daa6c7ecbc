/**
 * The full-window 3D view: renderer, orbit camera, lights with shadows, floor and grid, the
 * live arm, the translucent ghost and the target marker. One requestAnimationFrame loop reads
 * the store by mutation (no React, no allocation per frame) and renders only when something
 * moved. The first frame is drawn after every mesh has loaded (`load()` resolves).
 */
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { URDFJoint, URDFRobot } from 'urdf-loader';
import type { ArmStore } from '../store/ArmStore.ts';
import type { TargetPreview } from '../store/TargetPreview.ts';
import { ghostPose } from '../store/ghostPose.ts';
import { SERVO_JOINTS, jointValueFromAngle } from '../model/armModel.ts';
import type { JointMap } from '../robots/robotSpec.ts';
import { frameCamera, type GhostSource } from '../robots/sceneHooks.ts';
import { RobotModelLoader, solidMaterial } from './loadRobot.ts';
import { createStage, ghostMaterial, type Stage } from './stage.ts';
import { ResolutionGovernor } from './ResolutionGovernor.ts';
import { isSoftwareWebGL } from './webglInfo.ts';
import type { ReplayPlayer } from '../replay/ReplayPlayer.ts';
import { ReplaySibling, siblingMaterial } from '../replay/ReplaySibling.ts';

const MM = 0.001;
const GHOST_HIDDEN_LINKS = ['base_link', 'turret', 'rail'];
/** Idle time after which a full-resolution frame is drawn, ms. */
const REFINE_AFTER_MS = 300;

export class Viewer {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly stage: Stage;
  private robot: URDFRobot | null = null;
  private ghost: URDFRobot | null = null;
  private robotJoints: (URDFJoint | undefined)[] = [];
  private ghostJoints: (URDFJoint | undefined)[] = [];
  /** The replay's sibling arm (History panel), when a ReplayPlayer is given. */
  private sibling: ReplaySibling | null = null;
  private ghostAngles: Float64Array;
  /** Servo i's URDF joint and store angle → joint value (armtwin5's when none is given). */
  private joints: JointMap | null = null;
  /** Drawn into the ghost instead of the target/commanded pose while active (the plan preview). */
  ghostSource: GhostSource | null = null;
  /** Called every frame (waypoint spheres, …); a hook returning true asks for a render. */
  readonly frameHooks = new Set<(now: number) => boolean>();
  private needsRender = true;
  /**
   * Whether a shadow caster moved since the shadow map was drawn. The map is drawn only then
   * (`shadowMap.autoUpdate` is off): an orbiting camera or a moving ghost re-renders the view
   * but not the shadows.
   */
  private shadowsDirty = true;
  private frame = 0;
  private running = false;
  /** Frames actually rendered (for the debug hook). */
  renderedFrames = 0;
  /** Shadow maps drawn (for the debug hook): only when a shadow caster moved. */
  shadowUpdates = 0;
  /** Whether WebGL runs in software (no MSAA then, see the constructor). */
  readonly software: boolean;
  /** Called after each rendered frame with its `performance.now()` (bench probe, tests). */
  readonly renderHooks = new Set<(now: number) => void>();

  /** The canvas's current pixel ratio (lowered while frames are slow). */
  get pixelRatio(): number {
    return this.governor.ratio;
  }
  private readonly raycaster = new THREE.Raycaster();
  private readonly pointer = new THREE.Vector2();
  private readonly hit = new THREE.Vector3();
  private downAt: { x: number; y: number } | null = null;
  private readonly governor: ResolutionGovernor;
  /** When the previous tick rendered (NaN if it did not): frame cost while moving. */
  private lastRenderAt = NaN;
  /** Frames rendered back to back after loading, so the resolution fits the machine at once. */
  private warmupFrames = 8;
  /** Whether the idle frame at full resolution has been drawn since the last motion. */
  private refined = true;
  private lastMovedAt = 0;

  constructor(
    private readonly container: HTMLElement,
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
    private readonly replay: ReplayPlayer | null = null,
  ) {
    this.ghostAngles = new Float64Array(store.servoCount);
    // Software WebGL (SwiftShader, llvmpipe) pays for every multisampled pixel on the CPU, and
    // the page waits for it: no MSAA there (the resolution governor's scaling smooths edges).
    this.software = isSoftwareWebGL();
    this.renderer = new THREE.WebGLRenderer({ antialias: !this.software });
    this.governor = new ResolutionGovernor({ maxRatio: Math.min(window.devicePixelRatio || 1, 2) });
    this.renderer.setPixelRatio(this.governor.ratio);
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    this.renderer.shadowMap.autoUpdate = false;
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.renderer.domElement.setAttribute('aria-label', '3D view of the arm');
    this.renderer.domElement.setAttribute('role', 'img');
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 20);
    this.camera.position.set(0.86, 0.6, 1.0);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0.21, 0);
    this.controls.enableDamping = false;
    this.controls.maxDistance = 4;
    this.controls.addEventListener('change', () => (this.needsRender = true));
    this.stage = createStage(this.scene);
  }

  /** The arm's z-up frame (metres), the camera and the canvas, for the scene's add-ons. */
  get world(): THREE.Group {
    return this.stage.world;
  }
  get canvas(): HTMLCanvasElement {
    return this.renderer.domElement;
  }

  /** The URDF joint values drawn now (rad or m), live arm or ghost, in servo order. */
  jointValues(which: 'robot' | 'ghost' = 'robot'): number[] {
    const joints = which === 'robot' ? this.robotJoints : this.ghostJoints;
    return joints.map((j) => (j ? j.angle : NaN));
  }

  /**
   * Loads the live arm and the ghost (replacing any loaded before); rejects with a readable
   * message. `joints` maps servos to URDF joints (default: armtwin5's, one degree = one degree).
   */
  async load(urdfUrl: string, joints?: JointMap): Promise<void> {
    const loader = new RobotModelLoader(urdfUrl);
    const [robot, ghost] = await Promise.all([
      loader.build(solidMaterial),
      loader.build(ghostMaterial),
    ]);
    ghost.traverse((o) => {
      o.castShadow = false;
      o.renderOrder = 1;
    });
    // The fixed pedestal and the turntable only ever differ from the live arm's by yaw: leave
    // them out, so the ghost never flickers inside the live base.
    for (const name of GHOST_HIDDEN_LINKS) {
      for (const child of ghost.links[name]?.children ?? [])
        if ((child as { isURDFVisual?: boolean }).isURDFVisual) child.visible = false;
    }
    ghost.visible = false;
    const sibling = this.replay
      ? new ReplaySibling(await loader.build(siblingMaterial), this.replay)
      : null;
    for (const old of [this.robot, this.ghost, this.sibling?.robot])
      if (old) old.removeFromParent();
    this.robot = robot;
    this.ghost = ghost;
    this.joints = joints ?? null;
    const names = joints?.names ?? SERVO_JOINTS;
    this.robotJoints = names.map((n) => robot.joints[n]);
    this.ghostJoints = names.map((n) => ghost.joints[n]);
    this.ghostAngles = new Float64Array(names.length);
    this.stage.world.add(robot, ghost);
    this.sibling = sibling;
    if (sibling) this.stage.world.add(sibling.robot);
    if (joints) frameCamera(this, robot);
    this.needsRender = true;
    this.shadowsDirty = true;
  }

  /** Attaches the canvas and starts the loop (call after `load`). */
  start(): void {
    this.container.appendChild(this.renderer.domElement);
    this.resize();
    window.addEventListener('resize', this.resize);
    const el = this.renderer.domElement;
    el.addEventListener('pointerdown', this.onPointerDown);
    el.addEventListener('pointerup', this.onPointerUp);
    this.running = true;
    this.frame = requestAnimationFrame(this.tick);
  }

  private readonly resize = (): void => {
    const w = this.container.clientWidth || window.innerWidth;
    const h = this.container.clientHeight || window.innerHeight;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.needsRender = true;
  };

  private readonly tick = (): void => {
    if (!this.running) return;
    this.frame = requestAnimationFrame(this.tick);
    const now = performance.now();
    if (this.store.sample(now) && this.pose(this.robotJoints, this.store.rendered))
      this.needsRender = this.shadowsDirty = true;
    this.updateGhost(now);
    if (this.sibling?.update(now)) this.needsRender = this.shadowsDirty = true;
    // A hook may move something that casts a shadow (waypoint spheres): redraw the map too.
    for (const hook of this.frameHooks) if (hook(now)) this.needsRender = this.shadowsDirty = true;
    this.updateTarget();
    if (this.warmupFrames > 0) {
      this.warmupFrames--;
      this.needsRender = true;
    }
    if (this.needsRender) {
      this.needsRender = false;
      this.governor.frame(now - this.lastRenderAt);
      if (this.renderer.getPixelRatio() !== this.governor.ratio)
        this.renderer.setPixelRatio(this.governor.ratio);
      this.draw(now);
      this.lastRenderAt = now;
      this.lastMovedAt = now;
      this.refined = false;
    } else {
      this.lastRenderAt = NaN;
      this.refineWhenIdle(now);
    }
  };

  /**
   * Once nothing has moved for a moment, draws one frame at full resolution, so a lowered
   * resolution (see ResolutionGovernor) only ever shows while things move.
   */
  private refineWhenIdle(now: number): void {
    const full = this.governor.opts.maxRatio;
    if (this.refined || now - this.lastMovedAt < REFINE_AFTER_MS) return;
    this.refined = true;
    if (this.governor.ratio >= full) return;
    this.renderer.setPixelRatio(full);
    this.draw(now);
  }

  private draw(now: number): void {
    if (this.shadowsDirty) {
      this.renderer.shadowMap.needsUpdate = true;
      this.shadowsDirty = false;
      this.shadowUpdates++;
    }
    this.renderer.render(this.scene, this.camera);
    this.renderedFrames++;
    for (const hook of this.renderHooks) hook(now);
  }

  /** Sets the joints to servo angles (degrees); true if any joint moved. */
  private pose(joints: (URDFJoint | undefined)[], angles: ArrayLike<number>): boolean {
    let changed = false;
    const m = this.joints;
    for (let i = 0; i < joints.length; i++) {
      const a = angles[i] ?? NaN;
      const v = m ? m.scale[i]! * a + m.bias[i]! : jointValueFromAngle(a);
      if (!Number.isNaN(a) && joints[i]?.setJointValue(v)) changed = true;
    }
    return changed;
  }

  private updateGhost(now: number): void {
    const ghost = this.ghost;
    if (!ghost) return;
    const t = this.target;
    const shows = !t.ghostEnabled
      ? 'nothing'
      : this.ghostSource?.sample(now, this.ghostAngles)
        ? 'plan'
        : ghostPose(
            {
              arm: this.store.opts.arm,
              rendered: this.store.rendered,
              commandedPwm: this.store.commandedPwm,
              previewOk: t.active && t.code === 0,
              previewAngles: t.angles,
            },
            this.ghostAngles,
          );
    t.ghostShows = shows;
    const visible = shows !== 'nothing';
    if (ghost.visible !== visible) {
      ghost.visible = visible;
      this.needsRender = true;
    }
    if (visible && this.pose(this.ghostJoints, this.ghostAngles)) this.needsRender = true;
  }

  private updateTarget(): void {
    const t = this.target;
    const m = this.stage.marker;
    if (m.visible !== t.active) {
      m.visible = t.active;
      this.needsRender = true;
    }
    if (!t.active) return;
    const x = t.x * MM;
    const y = t.y * MM;
    const z = t.z * MM;
    if (
      m.position.x !== x ||
      m.position.y !== y ||
      m.position.z !== z ||
      this.stage.markerOk !== (t.code === 0)
    ) {
      this.stage.placeMarker(x, y, z, t.code === 0);
      this.needsRender = true;
    }
  }

  private readonly onPointerDown = (e: PointerEvent): void => {
    this.downAt = e.button === 0 ? { x: e.clientX, y: e.clientY } : null;
  };

  /** A click (not a drag) on the floor places the Cartesian target there. */
  private readonly onPointerUp = (e: PointerEvent): void => {
    const d = this.downAt;
    this.downAt = null;
    if (!d || Math.hypot(e.clientX - d.x, e.clientY - d.y) > 4) return;
    const rect = this.renderer.domElement.getBoundingClientRect();
    this.pointer.set(
      ((e.clientX - rect.left) / rect.width) * 2 - 1,
      -((e.clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(this.pointer, this.camera);
    if (!this.raycaster.ray.intersectPlane(this.stage.floorPlane, this.hit)) return;
    this.stage.world.worldToLocal(this.hit); // three's y-up → the arm's z-up frame, metres
    this.target.place(Math.round(this.hit.x / MM), Math.round(this.hit.y / MM));
  };

  /** Asks for a render on the next frame (e.g. after a settings change). */
  invalidate(): void {
    this.needsRender = this.shadowsDirty = true;
  }

  dispose(): void {
    this.running = false;
    cancelAnimationFrame(this.frame);
    window.removeEventListener('resize', this.resize);
    this.controls.dispose();
    this.renderer.dispose();
    this.renderer.domElement.remove();
  }
}
