/**
 * The 3D view's one runtime: the stage, live arm, ghost, replay sibling, target marker, keep-out
 * zones and the cameras' screens, drawn on a canvas with its own requestAnimationFrame loop, the
 * steps of a frame in one order. One class, two hosts behind the same messages (./sceneHost.ts):
 * the render worker (./renderWorker.ts, an OffscreenCanvas) and, where no worker can draw, the
 * page's main thread behind a port pair (./inThreadScene.ts, the page's own canvas). What it
 * reads (the store's drawn angles, the target, the plan preview, the sibling's pose, the orbit
 * camera) arrives from the page as `FrameInput` messages and is kept in one plain snapshot
 * (./SceneFrame.ts) that Ghost, TargetMarker and ReplaySibling read; the drawn angles are posed
 * for each frame's instant (./DrawnPose.ts). It renders only
 * when something moved, lowers the resolution while frames are slow and draws one
 * full-resolution frame once things rest (../FramePacer.ts); each drawn frame is reported
 * (`rendered`), and the page reads the report (./SceneReports.ts).
 */
import * as THREE from 'three';
import { frameCamera } from '../sceneHooks.ts';
import type { JointMap } from '../../core/robots/robotSpec.ts';
import { createStage, type Stage } from '../stage.ts';
import type { MeshFailure } from '../loadRobot.ts';
import { FramePacer, type FramePacerOptions } from '../FramePacer.ts';
import { TargetMarker } from '../TargetMarker.ts';
import { TranslucentTwin } from '../TranslucentTwin.ts';
import { ZonesView } from '../ZonesView.ts';
import { createRenderer } from '../createRenderer.ts';
import { createViewCamera, VIEW_HOME } from '../orbitView.ts';
import { loadArmSet, swapArmSet, type ArmSet } from '../ArmSet.ts';
import { emptySceneFrame, mergeFrame } from './SceneFrame.ts';
import { DrawnPose } from './DrawnPose.ts';
import { WorkerExtras } from './WorkerExtras.ts';
import type { FrameInput, FramedCamera, FromWorker, TrackingState } from './messages.ts';

type Rendered = Extract<FromWorker, { type: 'rendered' }>;

export class SceneRuntime {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = createViewCamera();
  /** The orbit target and range frameCamera sets (the page's OrbitControls take them over). */
  readonly controls = {
    target: new THREE.Vector3(...VIEW_HOME.target),
    maxDistance: VIEW_HOME.maxDistance as number,
    /** Aims the camera at the target (what OrbitControls' `update` does for a framed view). */
    update: (): void => this.camera.lookAt(this.controls.target),
  };
  private readonly stage: Stage;
  private readonly marker: TargetMarker;
  private readonly zones: ZonesView;
  private readonly extras: WorkerExtras;
  /** When to draw and at what resolution (the host says how: ./sceneHost.ts). */
  private readonly pacer: FramePacer;
  /** The live arm (painted by tracking error, as the page's store says), ghost and sibling. */
  private arms: ArmSet | null = null;
  private tracking: TrackingState = {
    active: false,
    version: 0,
    colours: new Int32Array(0),
    levels: [],
  };
  /** The page's state as last sent, and the live arm's pose for each frame. */
  private readonly frameState = emptySceneFrame();
  private readonly pose = new DrawnPose(this.frameState);
  /** The live arm drawn translucent over a camera's picture while the view looks through it. */
  private readonly twin = new TranslucentTwin();
  private viewingThrough = false;
  private needsRender = true;
  private shadowsDirty = true;
  /** The page's resize this canvas was last sized by (its frames say so). */
  private sizeSeq = 0;
  private frames = 0;
  private running = false;
  private frame = 0;

  constructor(
    canvas: OffscreenCanvas | HTMLCanvasElement,
    readonly software: boolean,
    dpr: number,
    private readonly post: (m: FromWorker) => void,
    pacing: Partial<FramePacerOptions> = {},
  ) {
    this.renderer = createRenderer(software, canvas);
    this.pacer = new FramePacer(this.renderer, Math.min(dpr || 1, 2), pacing);
    this.camera.lookAt(this.controls.target);
    this.stage = createStage(this.scene);
    this.extras = new WorkerExtras(this.scene, this.stage.world);
    this.marker = new TargetMarker(this.stage, this.frameState);
    this.zones = new ZonesView(this.stage.world);
  }

  /** The canvas's size in CSS pixels and the device's pixel ratio. */
  resize(width: number, height: number, dpr: number, seq = this.sizeSeq): void {
    this.sizeSeq = seq;
    this.pacer.governor.opts.maxRatio = Math.min(dpr || 1, 2);
    this.renderer.setSize(Math.max(1, width), Math.max(1, height), false);
    this.camera.aspect = width / Math.max(1, height);
    this.camera.updateProjectionMatrix();
    this.needsRender = true;
  }

  showZones(keepOut: Parameters<ZonesView['show']>[0]): string[] {
    if (this.zones.show(keepOut)) this.needsRender = true;
    return this.zones.names;
  }

  /** Loads the robot as the live arm, the ghost and (when asked) the replay's sibling. */
  async load(
    urdfUrl: string,
    joints: JointMap,
    withSibling: boolean,
  ): Promise<{ failures: MeshFailure[]; framed: FramedCamera }> {
    const arms = await loadArmSet(urdfUrl, joints, this.frameState, withSibling);
    swapArmSet(this.stage.world, this.arms, arms);
    this.arms = arms;
    const robot = arms.live.robot;
    frameCamera(this as unknown as Parameters<typeof frameCamera>[0], robot);
    this.applyTwinLook();
    arms.sibling?.standClearOf(robot);
    this.needsRender = this.shadowsDirty = true;
    const p = this.camera.position;
    const t = this.controls.target;
    return {
      failures: arms.failures,
      framed: {
        position: [p.x, p.y, p.z],
        target: [t.x, t.y, t.z],
        far: this.camera.far,
        maxDistance: this.controls.maxDistance,
      },
    };
  }

  /** See WorkerExtras.set; looking through a camera, the twin goes translucent over it. */
  setExtras(objects: unknown[], sceneObjects: unknown[], hidden: number[]): void {
    this.viewingThrough = this.extras.set(objects, sceneObjects, hidden);
    this.applyTwinLook();
    this.needsRender = this.shadowsDirty = true;
  }

  private applyTwinLook(): void {
    const robot = this.arms?.live.robot ?? null;
    if (this.viewingThrough && robot) {
      if (this.twin.root !== robot) this.twin.apply(robot);
    } else this.twin.restore();
  }

  /** A new picture for the mesh `uuid`'s texture (a camera's frame). */
  setTexture(uuid: string, bitmap: ImageBitmap): void {
    this.extras.setTexture(uuid, bitmap);
    this.needsRender = true;
  }

  /** Takes what the page sent; drawn on the next frame. */
  take(m: FrameInput): void {
    mergeFrame(this.frameState, m);
    this.pose.take(m);
    if (m.camera) {
      const c = m.camera;
      this.camera.position.fromArray(c.position);
      this.camera.quaternion.fromArray(c.quaternion);
      this.camera.fov = c.fov;
      this.camera.near = c.near;
      this.camera.far = c.far;
      this.camera.updateProjectionMatrix();
      this.needsRender = true;
    }
    if (m.tracking) this.tracking = m.tracking;
    if (m.invalidate) this.needsRender = this.shadowsDirty = true;
  }

  /** The arm's z-up world as drawn (the live arm, ghost, sibling, zones): an in-thread page reads it. */
  get world(): THREE.Group {
    return this.stage.world;
  }

  /** The live arm's URDF model (null before a robot loads): an in-thread host's page reads it. */
  get liveRobot(): ArmSet['live']['robot'] | null {
    return this.arms?.live.robot ?? null;
  }

  start(): void {
    if (this.running) return;
    this.running = true;
    this.frame = requestAnimationFrame(this.tick);
  }

  /** Stops the loop and lets the WebGL context go (an in-thread host's end; a worker ends whole). */
  stop(): void {
    this.running = false;
    cancelAnimationFrame(this.frame);
    this.renderer.dispose();
  }

  private readonly tick = (): void => {
    if (!this.running) return;
    this.frame = requestAnimationFrame(this.tick);
    const now = performance.now();
    const a = this.arms;
    if (this.pose.poseAt(performance.timeOrigin + now) && a?.live.pose(this.frameState.rendered))
      this.needsRender = this.shadowsDirty = true;
    if (a?.ghost.update()) this.needsRender = true;
    if (a?.sibling?.update()) this.needsRender = this.shadowsDirty = true;
    if (this.marker.update()) this.needsRender = true;
    if (a?.tracking.update(this.tracking)) this.needsRender = true;
    const moved = this.needsRender;
    this.needsRender = false;
    this.pacer.step(now, moved, this.draw);
  };

  private readonly draw = (): void => {
    if (this.shadowsDirty) {
      this.renderer.shadowMap.needsUpdate = true;
      this.shadowsDirty = false;
    }
    this.renderer.render(this.scene, this.camera);
    this.pose.drawn(performance.timeOrigin + performance.now());
    this.frames++;
    const a = this.arms;
    const report: Rendered = {
      type: 'rendered',
      at: performance.timeOrigin + performance.now(),
      frames: this.frames,
      sizeSeq: this.sizeSeq,
      pixelRatio: this.renderer.getPixelRatio(),
      costMs: this.pacer.costMs,
      aheadMs: this.pose.aheadMs,
      robot: a?.live.values() ?? [],
      ghost: a?.ghost.posed.values() ?? [],
      sibling: a?.sibling?.posed.values() ?? [],
      ghostShows: a?.ghost.shows ?? 'nothing',
      ghostPainted: a?.ghost.painted ?? '',
      trackingLevels: a ? a.tracking.levels.slice() : null,
    };
    this.post(report);
  };
}
