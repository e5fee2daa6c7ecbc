/**
 * The full-window 3D view and its one requestAnimationFrame loop: renderer, orbit camera, the
 * stage (./stage.ts), the live arm, the ghost (./Ghost.ts), the replay's sibling and the target
 * marker (./TargetMarker.ts), all posed through the active robot's joint map (./PosedRobot.ts).
 * The loop reads the store by mutation (no React, no allocation per frame) and renders only when
 * something moved. The first frame is drawn after every mesh has loaded (`load()` resolves).
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { ArmStore } from '../core/store/ArmStore.ts';
import type { TargetPreview } from '../core/store/TargetPreview.ts';
import type { JointMap } from '../core/robots/robotSpec.ts';
import { frameCamera, type GhostSource } from './sceneHooks.ts';
import type { SiblingSource } from './ReplaySibling.ts';
import type { MeshFailure } from './loadRobot.ts';
import { MeshFailureNote } from './MeshFailureNote.ts';
import { createStage, type Stage } from './stage.ts';
import { ZonesView } from './ZonesView.ts';
import type { ProfileKeepOut } from '@armtwin/robot';
import { TargetMarker } from './TargetMarker.ts';
import { FloorPicker } from './FloorPicker.ts';
import { FramePacer } from './FramePacer.ts';
import type { TrackingPaint } from './TrackingPaint.ts';
import { isSoftwareWebGL } from './webglInfo.ts';
import { createRenderer } from './createRenderer.ts';
import { createOrbitControls, createViewCamera } from './orbitView.ts';
import { loadArmSet, swapArmSet, type ArmSet } from './ArmSet.ts';
import type { DrawnRobot, SceneView } from './SceneView.ts';

export type { DrawnRobot } from './SceneView.ts';

export class Viewer implements SceneView {
  readonly thread = 'main' as const;
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly stage: Stage;
  /** The live arm, its tracking paint, the ghost and the replay's sibling (with a ReplayPlayer). */
  private arms: ArmSet | null = null;
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
  /** When to draw and at what resolution; 8 frames back to back first, so it fits the machine. */
  private readonly pacer: FramePacer;

  constructor(
    private readonly container: HTMLElement,
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
    private readonly replay: SiblingSource | null = null,
  ) {
    // The page waits for software WebGL's every pixel: no MSAA there (./createRenderer.ts).
    this.software = isSoftwareWebGL();
    this.renderer = createRenderer(this.software);
    this.pacer = new FramePacer(this.renderer, Math.min(window.devicePixelRatio || 1, 2), {
      warmupFrames: 8,
    });
    this.renderer.domElement.setAttribute('aria-label', '3D view of the arm');
    this.renderer.domElement.setAttribute('role', 'img');
    this.camera = createViewCamera();
    this.controls = createOrbitControls(
      this.camera,
      this.renderer.domElement,
      () => (this.needsRender = true),
    );
    this.stage = createStage(this.scene);
    this.marker = new TargetMarker(this.stage, target);
    this.zones = new ZonesView(this.stage.world);
    this.picker = new FloorPicker(this.renderer.domElement, this.camera, this.stage, target);
    this.failureNote = new MeshFailureNote(container);
  }

  /** The canvas's current pixel ratio (lowered while frames are slow). */
  get pixelRatio(): number {
    return this.pacer.governor.ratio;
  }
  /** The page's frames run unbudgeted (the render worker budgets software WebGL's). */
  get frameCostMs(): number {
    return this.pacer.costMs;
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
    return this.arms?.live.robot ?? null;
  }

  /** The live arm's links painted by tracking error (store.tracking). */
  get tracking(): TrackingPaint | null {
    return this.arms?.tracking ?? null;
  }

  /** Draws the active robot's keep-out zones (its profile's `keepOut`). */
  showZones(keepOut: ProfileKeepOut | undefined): void {
    if (this.zones.show(keepOut)) this.needsRender = true;
  }

  /** The URDF joint whose child link the ghost paints red ('' = none): a refused target's. */
  get ghostPainted(): string {
    return this.arms?.ghost.painted ?? '';
  }

  /** The URDF joint values drawn now (rad or m), in servo order ([] before a robot loads). */
  jointValues(which: DrawnRobot = 'robot'): number[] {
    const a = this.arms;
    const posed =
      which === 'robot' ? a?.live : which === 'ghost' ? a?.ghost.posed : a?.sibling?.posed;
    return posed?.values() ?? [];
  }

  /**
   * Loads a robot's URDF as the live arm, the ghost and (with a ReplayPlayer) the replay's
   * sibling, replacing any loaded before, all three posed through `joints` (the active robot's
   * profile); rejects with a readable message when the URDF cannot be used. A mesh that does
   * not load is left out, counted and named over the view (`meshFailures`), and the rest is drawn.
   */
  async load(urdfUrl: string, joints: JointMap): Promise<void> {
    const arms = await loadArmSet(urdfUrl, joints, this.store, this.target, this.replay);
    this.meshFailures = arms.failures;
    this.failureNote.show(arms.failures);
    swapArmSet(this.stage.world, this.arms, arms);
    this.arms = arms;
    const robot = arms.live.robot;
    frameCamera(this, robot);
    arms.sibling?.standClearOf(robot);
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
    const a = this.arms;
    if (this.store.sample(now) && a?.live.pose(this.store.rendered))
      this.needsRender = this.shadowsDirty = true;
    if (a?.tracking.update(this.store.tracking)) this.needsRender = true;
    if (a?.ghost.update(now, this.ghostSource)) this.needsRender = true;
    if (a?.sibling?.update(now)) this.needsRender = this.shadowsDirty = true;
    // A hook may move something that casts a shadow (waypoint spheres): redraw the map too.
    for (const hook of this.frameHooks) if (hook(now)) this.needsRender = this.shadowsDirty = true;
    if (this.marker.update()) this.needsRender = true;
    const moved = this.needsRender;
    this.needsRender = false;
    this.pacer.step(now, moved, this.draw);
  };

  private readonly draw = (now: number): void => {
    if (this.shadowsDirty) {
      this.renderer.shadowMap.needsUpdate = true;
      this.shadowsDirty = false;
      this.shadowUpdates++;
    }
    this.renderer.render(this.scene, this.camera);
    this.store.frameShown(performance.now());
    this.renderedFrames++;
    for (const hook of this.renderHooks) hook(now);
  };

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
