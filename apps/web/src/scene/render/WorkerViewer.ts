/**
 * The 3D view drawn by the render worker (./renderWorker.ts), as the page sees it: the same
 * SceneView the main-thread Viewer offers. The page keeps what must answer at once or read its
 * own state — the orbit camera (OrbitControls on the real canvas element, which still gets the
 * pointer and wheel events after `transferControlToOffscreen`), floor picking, the Plan panel's
 * waypoint raycasts (against this page-side scene), the store and the replay — and, on its own
 * light requestAnimationFrame loop, sends the worker only what changed (`FrameInput`): the drawn
 * angles, commanded pulses, target, plan preview, sibling pose and camera. WebGL and the meshes
 * live only in the worker. What the worker drew comes back with each frame (joint values, the
 * ghost's state) for the debug hook, the Ghost panel and the bench's probe.
 */
import * as THREE from 'three';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { ProfileKeepOut } from '@armtwin/robot';
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { SiblingSource } from '../ReplaySibling.ts';
import type { JointMap } from '../../core/robots/robotSpec.ts';
import type { GhostSource } from '../sceneHooks.ts';
import { createStage, type Stage } from '../stage.ts';
import { FloorPicker } from '../FloorPicker.ts';
import { MeshFailureNote } from '../MeshFailureNote.ts';
import type { MeshFailure } from '../loadRobot.ts';
import type { DrawnRobot, SceneView } from '../SceneView.ts';
import { createOrbitControls, createViewCamera } from '../orbitView.ts';
import type { FrameInput, FromWorker, ToWorker } from './messages.ts';
import { cameraState } from './snapshots.ts';
import { ExtrasSender } from './ExtrasSender.ts';
import { FrameChanges } from './FrameChanges.ts';

/** Where the render worker comes from (a test or another bundler may hand in its own). */
export type MakeRenderWorker = () => Worker;

/** The worker, bundled by Vite from ./renderWorker.ts. */
export const makeRenderWorker: MakeRenderWorker = () =>
  new Worker(new URL('./renderWorker.ts', import.meta.url), { type: 'module', name: 'render' });

export class WorkerViewer implements SceneView {
  readonly thread = 'worker' as const;
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
  renderedFrames = 0;
  pixelRatio = 1;
  frameCostMs = 0;
  software = false;
  /** WebGL's renderer string in the worker ('' until it answered). */
  webglRenderer = '';
  ghostPainted = '';
  /** The last error the worker reported ('' = none). */
  lastError = '';
  /** What the worker's tracking paint shows (as the main-thread Viewer's `tracking`). */
  tracking: { levels: readonly string[] } | null = null;
  /** Called with the reason when the worker fails (./FallbackSceneView.ts falls back). */
  onFailure: ((reason: string) => void) | null = null;
  private zoneNames: string[] = [];
  private drawn: Record<DrawnRobot, number[]> = { robot: [], ghost: [], sibling: [] };
  private readonly stage: Stage;
  private readonly picker: FloorPicker;
  private readonly failureNote: MeshFailureNote;
  private readonly worker: Worker;
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
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
    private readonly replay: SiblingSource | null = null,
    /** Whether software WebGL's frames are paced (../FramePacer.ts; `?frames=full`: not). */
    private readonly pace = true,
    makeWorker: MakeRenderWorker = makeRenderWorker,
  ) {
    const canvas = document.createElement('canvas');
    canvas.setAttribute('aria-label', '3D view of the arm');
    canvas.setAttribute('role', 'img');
    canvas.dataset.render = 'worker';
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
    this.worker = makeWorker();
    this.worker.onmessage = (e: MessageEvent<FromWorker>) => this.onMessage(e.data);
    this.worker.onerror = (e) => this.fail(`render worker: ${e.message || 'failed to start'}`);
    this.resizeObserver = new ResizeObserver(() => this.resize());
    const offscreen = canvas.transferControlToOffscreen();
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
      [offscreen],
    );
  }

  get world(): THREE.Group {
    return this.stage.world;
  }
  /** The page holds no copy of the robot's meshes: they live in the worker. */
  get liveRobot(): null {
    return null;
  }
  get zones(): { readonly names: string[] } {
    return { names: this.zoneNames };
  }

  jointValues(which: DrawnRobot = 'robot'): number[] {
    return this.drawn[which].slice();
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
    this.store.drawnAheadMs = 0; // a fallback's page-side frames add no lead of their own
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
        // A frame drawn before the latest resize was wiped by it: not yet a frame on screen.
        if (m.sizeSeq === this.sizeSeq) this.renderedFrames = m.frames;
        this.pixelRatio = m.pixelRatio;
        this.frameCostMs = m.costMs;
        this.store.drawnAheadMs = m.aheadMs;
        this.drawn = { robot: m.robot, ghost: m.ghost, sibling: m.sibling };
        this.ghostPainted = m.ghostPainted;
        this.tracking = m.trackingLevels ? { levels: m.trackingLevels } : null;
        this.target.ghostShows = m.ghostShows;
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
