/**
 * The full-window 3D view and its one requestAnimationFrame loop: renderer, orbit camera, the
 * stage (./stage.ts), the live arm, the ghost (./Ghost.ts), the replay's sibling and the target
 * marker (./TargetMarker.ts), all posed through the active robot's joint map (./PosedRobot.ts).
 * The loop reads the store by mutation (no React, no allocation per frame) and renders only when
 * something moved. The first frame is drawn after every mesh has loaded (`load()` resolves).
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { ArmStore } from '../store/ArmStore.ts';
import type { TargetPreview } from '../store/TargetPreview.ts';
import type { JointMap } from '../robots/robotSpec.ts';
import { frameCamera, type GhostSource } from '../robots/sceneHooks.ts';
import type { ReplayPlayer } from '../replay/ReplayPlayer.ts';
import { ReplaySibling, siblingMaterial } from './ReplaySibling.ts';
import { RobotModelLoader, solidMaterial, type MeshFailure } from './loadRobot.ts';
import { MeshFailureNote } from './MeshFailureNote.ts';
import { createStage, type Stage } from './stage.ts';
import { Ghost, ghostMaterial } from './Ghost.ts';
import { ZonesView } from './ZonesView.ts';
import type { ProfileKeepOut } from '@armtwin/ik';
import { PosedRobot } from './PosedRobot.ts';
import { TargetMarker } from './TargetMarker.ts';
import { FloorPicker } from './FloorPicker.ts';
import { ResolutionGovernor } from './ResolutionGovernor.ts';
import { TrackingPaint } from './TrackingPaint.ts';
import { isSoftwareWebGL } from './webglInfo.ts';
import type { DrawnRobot, SceneView } from './SceneView.ts';

/** Idle time after which a full-resolution frame is drawn, ms. */
const REFINE_AFTER_MS = 300;

export type { DrawnRobot } from './SceneView.ts';

export class Viewer implements SceneView {
  readonly thread = 'main' as const;
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly stage: Stage;
  private live: PosedRobot | null = null;
  /** The live arm's links painted by tracking error (store.tracking). */
  tracking: TrackingPaint | null = null;
  private ghost: Ghost | null = null;
  /** The replay's sibling arm (History panel), when a ReplayPlayer is given. */
  private sibling: ReplaySibling | null = null;
  private readonly marker: TargetMarker;
  /** The active robot's keep-out zones, translucent. */
  readonly zones: ZonesView;
  private readonly picker: FloorPicker;
  private readonly failureNote: MeshFailureNote;
  /** The meshes of the loaded robot that could not be loaded (shown over the view). */
  meshFailures: readonly MeshFailure[] = [];
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
    this.marker = new TargetMarker(this.stage, target);
    this.zones = new ZonesView(this.stage.world);
    this.picker = new FloorPicker(this.renderer.domElement, this.camera, this.stage, target);
    this.failureNote = new MeshFailureNote(container);
  }

  /** The canvas's current pixel ratio (lowered while frames are slow). */
  get pixelRatio(): number {
    return this.governor.ratio;
  }

  /** The arm's z-up frame (metres), the camera and the canvas, for the scene's add-ons. */
  get world(): THREE.Group {
    return this.stage.world;
  }
  get canvas(): HTMLCanvasElement {
    return this.renderer.domElement;
  }
  /** The live arm's URDF model (null before a robot loads); replaced when another loads. */
  get liveRobot(): URDFRobot | null {
    return this.live?.robot ?? null;
  }

  /** Draws the active robot's keep-out zones (its profile's `keepOut`). */
  showZones(keepOut: ProfileKeepOut | undefined): void {
    if (this.zones.show(keepOut)) this.needsRender = true;
  }

  /** The URDF joint whose child link the ghost paints red ('' = none): a refused target's. */
  get ghostPainted(): string {
    return this.ghost?.painted ?? '';
  }

  /** The URDF joint values drawn now (rad or m), in servo order ([] before a robot loads). */
  jointValues(which: DrawnRobot = 'robot'): number[] {
    const posed =
      which === 'robot' ? this.live : which === 'ghost' ? this.ghost?.posed : this.sibling?.posed;
    return posed?.values() ?? [];
  }

  /**
   * Loads a robot's URDF as the live arm, the ghost and (with a ReplayPlayer) the replay's
   * sibling, replacing any loaded before, all three posed through `joints` (the active robot's
   * profile); rejects with a readable message when the URDF cannot be used. A mesh that does
   * not load is left out, counted and named over the view (`meshFailures`), and the rest is drawn.
   */
  async load(urdfUrl: string, joints: JointMap): Promise<void> {
    const loader = new RobotModelLoader(urdfUrl);
    const [built, builtGhost, builtSibling] = await Promise.all([
      loader.build(solidMaterial),
      loader.build(ghostMaterial),
      this.replay ? loader.build(siblingMaterial) : null,
    ]);
    const robot = built.robot;
    const ghost = builtGhost.robot;
    const sibling = builtSibling?.robot ?? null;
    this.meshFailures = built.failures;
    this.failureNote.show(built.failures);
    for (const old of [this.live?.robot, this.ghost?.robot, this.sibling?.robot])
      old?.removeFromParent();
    this.live = new PosedRobot(robot, joints);
    this.tracking?.dispose();
    this.tracking = new TrackingPaint(robot, joints.names);
    // Posed at once from the last sample: the store is sampled only when the arm moves, and an
    // arm at rest may not report a change for a long while (a fleet switch showed zeros).
    this.live.pose(this.store.rendered);
    this.ghost = new Ghost(new PosedRobot(ghost, joints), this.store, this.target);
    this.sibling =
      sibling && this.replay
        ? new ReplaySibling(new PosedRobot(sibling, joints), this.replay)
        : null;
    this.stage.world.add(robot, ghost);
    if (this.sibling) this.stage.world.add(this.sibling.robot);
    frameCamera(this, robot);
    this.sibling?.standClearOf(robot);
    this.needsRender = true;
    this.shadowsDirty = true;
  }

  /** Attaches the canvas and starts the loop (call after `load`). */
  start(): void {
    this.container.appendChild(this.renderer.domElement);
    this.resize();
    window.addEventListener('resize', this.resize);
    this.picker.attach();
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
    if (this.store.sample(now) && this.live?.pose(this.store.rendered))
      this.needsRender = this.shadowsDirty = true;
    if (this.tracking?.update(this.store.tracking)) this.needsRender = true;
    if (this.ghost?.update(now, this.ghostSource)) this.needsRender = true;
    if (this.sibling?.update(now)) this.needsRender = this.shadowsDirty = true;
    // A hook may move something that casts a shadow (waypoint spheres): redraw the map too.
    for (const hook of this.frameHooks) if (hook(now)) this.needsRender = this.shadowsDirty = true;
    if (this.marker.update()) this.needsRender = true;
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
    this.store.frameShown(performance.now());
    this.renderedFrames++;
    for (const hook of this.renderHooks) hook(now);
  }

  /** Asks for a render on the next frame (e.g. after a settings change). */
  invalidate(): void {
    this.needsRender = this.shadowsDirty = true;
  }

  dispose(): void {
    this.running = false;
    cancelAnimationFrame(this.frame);
    window.removeEventListener('resize', this.resize);
    this.picker.detach();
    this.controls.dispose();
    this.renderer.dispose();
    this.renderer.domElement.remove();
  }
}
