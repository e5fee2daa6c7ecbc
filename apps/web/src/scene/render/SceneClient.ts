/**
 * The page side of the 3D view, wherever the scene runtime (./SceneRuntime.ts) is hosted: in the
 * render worker (./renderWorker.ts) or on the main thread (./inThreadScene.ts), behind the same
 * messages (./messages.ts). It is the SceneView the page's other parts use. The page keeps what
 * must answer at once or read its own state — the orbit camera (OrbitControls on the canvas
 * element, which still gets the pointer and wheel events after `transferControlToOffscreen`),
 * floor picking, the Plan panel's waypoint raycasts (against this page-side scene), the store and
 * the replay — and, on its own light requestAnimationFrame loop, sends the runtime only what
 * changed (`FrameInput`): the drawn angles, commanded pulses, target, plan preview, sibling pose
 * and camera. What the runtime drew comes back with each frame and is kept, read-only, in
 * `reports` (./SceneReports.ts) for the debug hook, the Status and Ghost panels and the bench's
 * probe; nothing of it is written into the store.
 */
import * as THREE from 'three';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { ProfileKeepOut } from '@armtwin/robot';
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { SiblingSource } from '../../core/store/viewSources.ts';
import type { JointMap } from '../../core/robots/robotSpec.ts';
import type { GhostSource } from '../sceneHooks.ts';
import { createStage, type Stage } from '../stage.ts';
import { FloorPicker } from '../FloorPicker.ts';
import { MeshFailureNote } from '../MeshFailureNote.ts';
import type { MeshFailure } from '../loadRobot.ts';
import type { DrawnRobot, SceneView } from '../SceneView.ts';
import { createOrbitControls, createViewCamera } from '../orbitView.ts';
import type { FrameInput, FromWorker, ToWorker } from './messages.ts';
import type { RenderThread } from '../SceneView.ts';
import { SceneReports, type ReadonlySceneReports } from './SceneReports.ts';
import type { SceneRuntime } from './SceneRuntime.ts';
import { cameraState } from './snapshots.ts';
import { ExtrasSender } from './ExtrasSender.ts';
import { FrameChanges } from './FrameChanges.ts';

/** The page's end of the runtime's port: a Worker, or ./inThreadScene.ts's channel. */
export interface SceneChannel {
  postMessage(m: ToWorker, transfer: Transferable[]): void;
  onmessage: ((e: MessageEvent<FromWorker>) => void) | null;
  onerror: ((e: ErrorEvent) => void) | null;
  terminate(): void;
  /** The runtime itself where it runs on this thread (its live arm is readable then). */
  readonly runtime?: SceneRuntime | null;
}

/** Where the runtime is hosted: opens its channel for the page's `canvas`. */
export interface SceneHosting {
  readonly thread: RenderThread;
  /** Whether the canvas is handed over (`transferControlToOffscreen`) with `init`. */
  readonly offscreen: boolean;
  open(canvas: HTMLCanvasElement): SceneChannel;
}

/** The render worker, bundled by Vite from ./renderWorker.ts. */
export const WORKER_HOSTING: SceneHosting = {
  thread: 'worker',
  offscreen: true,
  open: () =>
    new Worker(new URL('./renderWorker.ts', import.meta.url), {
      type: 'module',
      name: 'render',
    }) as unknown as SceneChannel,
};

export class SceneClient implements SceneView {
  readonly thread: RenderThread;
  readonly scene = new THREE.Scene();
  readonly camera = createViewCamera();
  readonly controls: OrbitControls;
  readonly canvas: HTMLCanvasElement;
  readonly frameHooks = new Set<(now: number) => boolean>();
  readonly renderHooks = new Set<(now: number) => void>();
  /** Stands in for the WebGL renderer (the bench's probe wraps `render`): called per drawn frame. */
  readonly renderer = { render: (_scene: THREE.Scene, _camera: THREE.Camera): void => {} };
  ghostSource: GhostSource | null = null;
  meshFailures: readonly MeshFailure[] = [];
  /** What the runtime said of its last drawn frame (read-only for everyone else). */
  readonly reports: ReadonlySceneReports;
  private readonly report = new SceneReports();
  software = false;
  /** WebGL's renderer string in the worker ('' until it answered). */
  webglRenderer = '';
  /** The last error the runtime reported ('' = none). */
  lastError = '';
  /** Called with the reason when the runtime fails (./FallbackSceneView.ts falls back). */
  onFailure: ((reason: string) => void) | null = null;
  private zoneNames: string[] = [];
  private readonly stage: Stage;
  private readonly picker: FloorPicker;
  private readonly failureNote: MeshFailureNote;
  private readonly worker: SceneChannel;
  private readonly loads = new Map<number, { resolve(): void; reject(e: Error): void }>();
  private loadId = 0;
  private frame = 0;
  private running = false;
  private cameraDirty = true;
  private invalidated = false;
  /** What of the page's state changed since the last frame sent. */
  private readonly changes: FrameChanges;
  /** The page's resizes so far: a frame drawn at an older size (cleared since) is not counted. */
  private sizeSeq = 0;
  private readonly resizeObserver: ResizeObserver;
  /** What other parts added to the world or the scene, and the cameras' pictures. */
  private readonly extras: ExtrasSender;

  constructor(
    private readonly container: HTMLElement,
    store: ArmStore,
    target: TargetPreview,
    private readonly replay: SiblingSource | null = null,
    /** Whether software WebGL's frames are paced (../FramePacer.ts; `?frames=full`: not). */
    private readonly pace = true,
    hosting: SceneHosting = WORKER_HOSTING,
  ) {
    this.thread = hosting.thread;
    this.reports = this.report;
    const canvas = document.createElement('canvas');
    canvas.setAttribute('aria-label', '3D view of the arm');
    canvas.setAttribute('role', 'img');
    canvas.dataset.render = hosting.thread;
    canvas.style.display = 'block';
    canvas.style.width = '100%';
    canvas.style.height = '100%';
    this.canvas = canvas;
    this.controls = createOrbitControls(this.camera, canvas, () => (this.cameraDirty = true));
    this.controls.update();
    this.stage = createStage(this.scene);
    this.extras = new ExtrasSender(this.scene, this.stage.world, (m, t) => this.send(m, t));
    this.changes = new FrameChanges(store, target, replay);
    this.picker = new FloorPicker(canvas, this.camera, this.stage, target);
    this.failureNote = new MeshFailureNote(container);
    this.worker = hosting.open(canvas);
    this.worker.onmessage = (e: MessageEvent<FromWorker>) => this.onMessage(e.data);
    this.worker.onerror = (e) => this.fail(`render worker: ${e.message || 'failed to start'}`);
    this.resizeObserver = new ResizeObserver(() => this.resize());
    const offscreen = hosting.offscreen ? canvas.transferControlToOffscreen() : undefined;
    const { width, height } = this.size();
    this.send(
      {
        type: 'init',
        canvas: offscreen,
        width,
        height,
        dpr: window.devicePixelRatio || 1,
        pace: this.pace,
      },
      offscreen ? [offscreen] : [],
    );
  }

  get renderedFrames(): number {
    return this.report.frames;
  }
  get pixelRatio(): number {
    return this.report.pixelRatio;
  }
  get frameCostMs(): number {
    return this.report.costMs;
  }
  get ghostPainted(): string {
    return this.report.ghostPainted;
  }
  /** What the runtime's tracking paint shows. */
  get tracking(): { levels: readonly string[] } | null {
    const levels = this.report.trackingLevels;
    return levels ? { levels } : null;
  }

  get world(): THREE.Group {
    return this.stage.world;
  }
  /**
   * The world the runtime draws (its live arm, ghost, sibling) where it runs on this thread; null
   * from a worker. End-to-end checks and console users look at the drawn meshes there.
   */
  get drawnWorld(): THREE.Group | null {
    return this.worker.runtime?.world ?? null;
  }

  /** The live arm's model where the runtime runs on this thread; null from a worker. */
  get liveRobot(): SceneView['liveRobot'] {
    return this.worker.runtime?.liveRobot ?? null;
  }
  get zones(): { readonly names: string[] } {
    return { names: this.zoneNames };
  }

  jointValues(which: DrawnRobot = 'robot'): number[] {
    return this.report.drawn(which);
  }

  showZones(keepOut: ProfileKeepOut | undefined): void {
    this.send({ type: 'zones', keepOut });
  }

  load(urdfUrl: string, joints: JointMap): Promise<void> {
    const id = ++this.loadId;
    const url = new URL(urdfUrl, document.baseURI).href;
    // The store may have been sized for this robot just before: its arm goes first.
    this.sendFrame(performance.now(), true);
    return new Promise<void>((resolve, reject) => {
      this.loads.set(id, { resolve, reject });
      this.send({ type: 'load', id, urdfUrl: url, joints, sibling: this.replay !== null });
    });
  }

  start(): void {
    this.container.appendChild(this.canvas);
    this.resizeObserver.observe(this.container);
    window.addEventListener('resize', this.resize);
    this.resize();
    this.picker.attach();
    this.running = true;
    this.frame = requestAnimationFrame(this.tick);
  }

  invalidate(): void {
    this.invalidated = true;
  }

  dispose(): void {
    this.running = false;
    cancelAnimationFrame(this.frame);
    this.resizeObserver.disconnect();
    window.removeEventListener('resize', this.resize);
    this.picker.detach();
    this.controls.dispose();
    this.worker.terminate();
    this.canvas.remove();
  }

  private send(m: ToWorker, transfer: Transferable[] = []): void {
    this.worker.postMessage(m, transfer);
  }

  private size(): { width: number; height: number } {
    return {
      width: this.container.clientWidth || window.innerWidth,
      height: this.container.clientHeight || window.innerHeight,
    };
  }

  private readonly resize = (): void => {
    const { width, height } = this.size();
    this.camera.aspect = width / Math.max(1, height);
    this.camera.updateProjectionMatrix();
    this.cameraDirty = true;
    this.sizeSeq++;
    this.send({
      type: 'resize',
      width,
      height,
      dpr: window.devicePixelRatio || 1,
      seq: this.sizeSeq,
    });
  };

  /** `t`: the frame's time (rAF's timestamp), the instant the arm is sampled for. */
  private readonly tick = (t: number): void => {
    if (!this.running) return;
    this.frame = requestAnimationFrame(this.tick);
    this.sendFrame(t, false);
  };

  /** Samples the page's state for `now` and sends the worker what changed (all with `full`). */
  private sendFrame(now: number, full: boolean): void {
    const m: FrameInput = { type: 'frame' };
    let any = this.changes.collect(m, now, full, this.running, this.ghostSource);
    for (const hook of this.frameHooks) if (hook(now)) this.invalidated = true;
    const invalidated = this.invalidated;
    if (invalidated) {
      this.invalidated = false;
      m.invalidate = true;
      any = true;
      this.extras.sync();
    }
    // A hook may have moved the camera itself (a camera's view): sent with any invalidation.
    if (this.cameraDirty || full || invalidated) {
      this.cameraDirty = false;
      m.camera = cameraState(this.camera);
      any = true;
    }
    this.extras.sendPictures();
    // Picking and waypoint raycasts read world matrices, which no render updates on this side.
    this.scene.updateMatrixWorld();
    this.camera.updateMatrixWorld();
    if (!any) return;
    this.send(m);
    this.changes.posted(m);
  }

  private onMessage(m: FromWorker): void {
    switch (m.type) {
      case 'ready':
        this.software = m.software;
        this.webglRenderer = m.renderer;
        break;
      case 'loaded': {
        this.meshFailures = m.failures;
        this.failureNote.show(m.failures);
        const f = m.framed;
        this.controls.target.fromArray(f.target);
        this.camera.position.fromArray(f.position);
        this.camera.far = f.far;
        this.camera.updateProjectionMatrix();
        this.controls.maxDistance = f.maxDistance;
        this.controls.update();
        this.cameraDirty = true;
        this.loads.get(m.id)?.resolve();
        this.loads.delete(m.id);
        break;
      }
      case 'loadFailed':
        this.loads.get(m.id)?.reject(new Error(m.message));
        this.loads.delete(m.id);
        break;
      case 'zones':
        this.zoneNames = m.names;
        break;
      case 'rendered': {
        this.report.take(m, this.sizeSeq);
        this.renderer.render(this.scene, this.camera);
        const now = m.at - performance.timeOrigin;
        // No display lead is learnt here: the worker poses each frame for its own instant
        // (./PoseCourse.ts), so the page samples for `now` itself.
        for (const hook of this.renderHooks) hook(now);
        break;
      }
      case 'error':
        this.fail(m.message);
        break;
    }
  }

  private fail(message: string): void {
    this.lastError = message;
    console.error(message);
    for (const [, l] of this.loads) l.reject(new Error(message));
    this.loads.clear();
    this.onFailure?.(message);
  }
}
