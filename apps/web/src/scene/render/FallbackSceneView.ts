/**
 * The 3D view that starts in the render worker and falls back to the main thread: when the
 * worker cannot start or fails before its first frame (its script does not load, no WebGL for an
 * OffscreenCanvas, an error it reports, the model failing to load there), the worker view is
 * disposed (its canvas, already handed to the worker, goes with it), a main-thread view is built
 * with a fresh canvas in its place, and what other parts gave the view moves over: the frame and
 * render hooks, the ghost source, the objects added to the world or scene (waypoints, camera
 * screens), the camera, the keep-out zones and the robot (loaded again). `onFallback(reason)`
 * tells the page (the Status panel says so). A failure after the first frame is only reported
 * by the worker view (console), as before. Every other member forwards to the current view.
 */
import type * as THREE from 'three';
import type { ProfileKeepOut } from '@armtwin/robot';
import type { JointMap } from '../../core/robots/robotSpec.ts';
import type { GhostSource } from '../sceneHooks.ts';
import type { DrawnRobot, RenderThread, SceneView } from '../SceneView.ts';

/** The worker view as this needs it: a SceneView that says when it failed. */
export interface FailingView extends SceneView {
  /** Set by FallbackSceneView: called with a reason when the worker fails. */
  onFailure: ((reason: string) => void) | null;
}

export interface FallbackFactories {
  /** Builds the worker view (may throw: no module workers, no OffscreenCanvas). */
  worker(): FailingView;
  /** Builds the main-thread view. */
  main(): SceneView;
}

export class FallbackSceneView implements SceneView {
  private current: SceneView;
  private fellBack = false;
  private started = false;
  private lastZones: { keepOut: ProfileKeepOut | undefined } | null = null;
  private lastLoad: { urdfUrl: string; joints: JointMap } | null = null;
  /** The worker view's own world and scene children (the rest was added by other parts). */
  private readonly ownWorld: Set<THREE.Object3D>;
  private readonly ownScene: Set<THREE.Object3D>;
  /** Settles when the main-thread view has loaded the robot after a fallback. */
  private reload: Promise<void> | null = null;

  constructor(
    private readonly make: FallbackFactories,
    private readonly onFallback: (reason: string) => void,
  ) {
    let view: FailingView | null = null;
    let reason = '';
    try {
      view = make.worker();
    } catch (err) {
      reason = err instanceof Error ? err.message : String(err);
    }
    if (view) {
      this.current = view;
      view.onFailure = (r) => this.fallBack(r);
    } else {
      this.current = make.main();
      this.fellBack = true;
      onFallback(reason || 'the render worker could not be built');
    }
    this.ownWorld = new Set(this.current.world.children);
    this.ownScene = new Set(this.current.scene.children);
  }

  /** The view drawing now (the debug hook's `viewer.current`). */
  get view(): SceneView {
    return this.current;
  }
  get thread(): RenderThread {
    return this.current.thread;
  }
  get scene(): THREE.Scene {
    return this.current.scene;
  }
  get camera(): THREE.PerspectiveCamera {
    return this.current.camera;
  }
  get controls(): SceneView['controls'] {
    return this.current.controls;
  }
  get world(): THREE.Group {
    return this.current.world;
  }
  get canvas(): HTMLCanvasElement {
    return this.current.canvas;
  }
  get liveRobot(): SceneView['liveRobot'] {
    return this.current.liveRobot;
  }
  get zones(): { readonly names: string[] } {
    return this.current.zones;
  }
  get ghostPainted(): string {
    return this.current.ghostPainted;
  }
  get meshFailures(): SceneView['meshFailures'] {
    return this.current.meshFailures;
  }
  get pixelRatio(): number {
    return this.current.pixelRatio;
  }
  get frameCostMs(): number {
    return this.current.frameCostMs;
  }
  get software(): boolean {
    return this.current.software;
  }
  get renderedFrames(): number {
    return this.current.renderedFrames;
  }
  get reports(): SceneView['reports'] {
    return this.current.reports;
  }
  /** The bench's probe wraps `renderer.render` (the WebGL renderer, or the worker view's stand-in). */
  get renderer(): unknown {
    return (this.current as unknown as { renderer?: unknown }).renderer;
  }
  get ghostSource(): GhostSource | null {
    return this.current.ghostSource;
  }
  set ghostSource(s: GhostSource | null) {
    this.current.ghostSource = s;
  }
  get frameHooks(): Set<(now: number) => boolean> {
    return this.current.frameHooks;
  }
  get renderHooks(): Set<(now: number) => void> {
    return this.current.renderHooks;
  }

  jointValues(which?: DrawnRobot): number[] {
    return this.current.jointValues(which);
  }

  showZones(keepOut: ProfileKeepOut | undefined): void {
    this.lastZones = { keepOut };
    this.current.showZones(keepOut);
  }

  load(urdfUrl: string, joints: JointMap): Promise<void> {
    this.lastLoad = { urdfUrl, joints };
    if (this.fellBack) return this.current.load(urdfUrl, joints);
    return this.current.load(urdfUrl, joints).catch((err: unknown) => {
      if (this.fellBack) return this.reload ?? this.current.load(urdfUrl, joints);
      if (this.current.renderedFrames > 0) throw err;
      const message = err instanceof Error ? err.message : String(err);
      this.fallBack(`the model failed to load there: ${message}`);
      return this.reload ?? Promise.resolve();
    });
  }

  start(): void {
    this.started = true;
    this.current.start();
  }

  invalidate(): void {
    this.current.invalidate();
  }

  dispose(): void {
    this.current.dispose();
  }

  /** Moves to the main thread when the worker failed before its first frame. */
  private fallBack(reason: string): void {
    const old = this.current;
    if (this.fellBack || old.renderedFrames > 0) return;
    this.fellBack = true;
    (old as FailingView).onFailure = null;
    const next = this.make.main();
    for (const hook of old.frameHooks) next.frameHooks.add(hook);
    for (const hook of old.renderHooks) next.renderHooks.add(hook);
    next.ghostSource = old.ghostSource;
    for (const o of [...old.world.children]) if (!this.ownWorld.has(o)) next.world.add(o);
    for (const o of [...old.scene.children]) {
      if (!this.ownScene.has(o) && o !== old.world) next.scene.add(o);
    }
    next.camera.position.copy(old.camera.position);
    next.controls.target.copy(old.controls.target);
    next.controls.update();
    old.dispose();
    this.current = next;
    if (this.lastZones) next.showZones(this.lastZones.keepOut);
    const load = this.lastLoad;
    this.reload = load ? next.load(load.urdfUrl, load.joints) : Promise.resolve();
    // Started already (the worker failed after the model loaded): start drawing once loaded.
    if (this.started)
      this.reload.then(
        () => next.start(),
        () => {}, // the load's caller hears of it
      );
    this.onFallback(reason);
  }
}
