/**
 * The 3D view as the render worker draws it (./renderWorker.ts): the same stage, live arm,
 * ghost, replay sibling, target marker and keep-out zones as the page's Viewer (../Viewer.ts),
 * built from the same classes, on an OffscreenCanvas, with the worker's own requestAnimationFrame
 * loop. What they read (the store's drawn angles, the target, the plan preview, the sibling's
 * pose, the orbit camera) arrives from the page as `FrameInput` messages and is copied into
 * small stand-ins (`mirror`), so Ghost, TargetMarker and ReplaySibling run unchanged. It renders
 * only when something moved, lowers the resolution while frames are slow (ResolutionGovernor)
 * and draws one full-resolution frame once things rest, as the Viewer does.
 */
import * as THREE from 'three';
import { DEMO_ARM } from '@armtwin/ik';
import { frameCamera } from '../../robots/sceneHooks.ts';
import type { JointMap } from '../../robots/robotSpec.ts';
import { TargetPreview } from '../../store/TargetPreview.ts';
import { createStage, type Stage } from '../stage.ts';
import { Ghost, ghostMaterial, type GhostStore } from '../Ghost.ts';
import { PosedRobot } from '../PosedRobot.ts';
import { ReplaySibling, siblingMaterial, type SiblingSource } from '../ReplaySibling.ts';
import { RobotModelLoader, solidMaterial, type MeshFailure } from '../loadRobot.ts';
import { ResolutionGovernor } from '../ResolutionGovernor.ts';
import { TargetMarker } from '../TargetMarker.ts';
import { TranslucentTwin } from '../TranslucentTwin.ts';
import { TrackingPaint } from '../TrackingPaint.ts';
import { ZonesView } from '../ZonesView.ts';
import type { FrameInput, FramedCamera, FromWorker, TrackingState } from './messages.ts';

/** Idle time after which a full-resolution frame is drawn, ms (as the Viewer). */
const REFINE_AFTER_MS = 300;

type Rendered = Extract<FromWorker, { type: 'rendered' }>;

/** The worker's copies of what the page's Ghost and ReplaySibling read. */
interface Mirror {
  store: {
    opts: { arm: GhostStore['opts']['arm'] };
    rendered: Float64Array;
    commandedPwm: Float64Array;
  };
  target: TargetPreview;
  plan: Float64Array | null;
  sibling: { active: boolean; record: unknown; angles: Float64Array; changed: boolean };
  renderedChanged: boolean;
}

export class WorkerScene {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(40, 1, 0.01, 20);
  /** The orbit target and range frameCamera sets (the page's OrbitControls take them over). */
  readonly controls = {
    target: new THREE.Vector3(0, 0.21, 0),
    maxDistance: 4,
    /** Aims the camera at the target (what OrbitControls' `update` does for a framed view). */
    update: (): void => this.camera.lookAt(this.controls.target),
  };
  private readonly stage: Stage;
  private readonly marker: TargetMarker;
  private readonly zones: ZonesView;
  private readonly governor: ResolutionGovernor;
  private live: PosedRobot | null = null;
  /** The live arm's links painted by tracking error, as the page's store says. */
  private trackingPaint: TrackingPaint | null = null;
  private tracking: TrackingState = {
    active: false,
    version: 0,
    colours: new Int32Array(0),
    levels: [],
  };
  private ghost: Ghost | null = null;
  private sibling: ReplaySibling | null = null;
  private readonly mirror: Mirror = {
    store: {
      opts: { arm: DEMO_ARM },
      rendered: new Float64Array(0),
      commandedPwm: new Float64Array(0),
    },
    target: new TargetPreview(),
    plan: null,
    sibling: { active: false, record: null, angles: new Float64Array(0), changed: false },
    renderedChanged: false,
  };
  private readonly siblingSource: SiblingSource;
  private readonly planSource = {
    sample: (_now: number, out: Float64Array): boolean => {
      const p = this.mirror.plan;
      if (!p) return false;
      for (let i = 0; i < out.length; i++) out[i] = p[i] ?? NaN;
      return true;
    },
  };
  private readonly objectLoader = new THREE.ObjectLoader();
  private extras: THREE.Object3D[] = [];
  /** The cameras' pictures, by the uuid of the mesh they go on. */
  private readonly textures = new Map<string, THREE.Texture>();
  /** The live arm drawn translucent over a camera's picture while the view looks through it. */
  private readonly twin = new TranslucentTwin();
  private viewingThrough = false;
  /** The stage's own scene children (floor, grid, lights), in the page's order. */
  private readonly ownScene: THREE.Object3D[];
  private needsRender = true;
  private shadowsDirty = true;
  /**
   * No warm-up burst here (the Viewer draws 8 frames back to back after loading so the
   * resolution fits the machine before the page waits on it): a slow frame in the worker holds
   * up nothing on the page, so the first frames are drawn at full resolution and the governor
   * lowers it only once things move.
   */
  private warmupFrames = 0;
  /** The page's resize this canvas was last sized by (its frames say so). */
  private sizeSeq = 0;
  private refined = true;
  private lastMovedAt = 0;
  private lastRenderAt = NaN;
  private frames = 0;
  private running = false;
  private maxRatio: number;

  constructor(
    private readonly canvas: OffscreenCanvas,
    readonly software: boolean,
    dpr: number,
    private readonly post: (m: FromWorker) => void,
  ) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: !software });
    this.maxRatio = Math.min(dpr || 1, 2);
    this.governor = new ResolutionGovernor({ maxRatio: this.maxRatio });
    this.renderer.setPixelRatio(this.governor.ratio);
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    this.renderer.shadowMap.autoUpdate = false;
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.camera.position.set(0.86, 0.6, 1.0);
    this.camera.lookAt(this.controls.target);
    this.stage = createStage(this.scene);
    this.ownScene = [...this.scene.children];
    this.marker = new TargetMarker(this.stage, this.mirror.target);
    this.zones = new ZonesView(this.stage.world);
    const sib = this.mirror.sibling;
    this.siblingSource = {
      update: () => {
        const c = sib.changed;
        sib.changed = false;
        return c;
      },
      get active() {
        return sib.active;
      },
      get record() {
        return sib.record;
      },
      get angles() {
        return sib.angles;
      },
    };
  }

  /** The canvas's size in CSS pixels and the device's pixel ratio. */
  resize(width: number, height: number, dpr: number, seq = this.sizeSeq): void {
    this.sizeSeq = seq;
    const r = Math.min(dpr || 1, 2);
    if (r !== this.maxRatio) {
      this.maxRatio = r;
      this.governor.opts.maxRatio = r;
    }
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
    const loader = new RobotModelLoader(urdfUrl);
    const [built, builtGhost, builtSibling] = await Promise.all([
      loader.build(solidMaterial),
      loader.build(ghostMaterial),
      withSibling ? loader.build(siblingMaterial) : null,
    ]);
    for (const old of [this.live?.robot, this.ghost?.robot, this.sibling?.robot])
      old?.removeFromParent();
    this.live = new PosedRobot(built.robot, joints);
    this.trackingPaint?.dispose();
    this.trackingPaint = new TrackingPaint(built.robot, joints.names);
    this.live.pose(this.mirror.store.rendered);
    this.ghost = new Ghost(
      new PosedRobot(builtGhost.robot, joints),
      this.mirror.store,
      this.mirror.target,
    );
    this.sibling = builtSibling
      ? new ReplaySibling(new PosedRobot(builtSibling.robot, joints), this.siblingSource)
      : null;
    this.stage.world.add(built.robot, builtGhost.robot);
    if (this.sibling) this.stage.world.add(this.sibling.robot);
    frameCamera(this as unknown as Parameters<typeof frameCamera>[0], built.robot);
    this.applyTwinLook();
    this.sibling?.standClearOf(built.robot);
    this.needsRender = this.shadowsDirty = true;
    const p = this.camera.position;
    const t = this.controls.target;
    return {
      failures: built.failures,
      framed: {
        position: [p.x, p.y, p.z],
        target: [t.x, t.y, t.z],
        far: this.camera.far,
        maxDistance: this.controls.maxDistance,
      },
    };
  }

  /**
   * Draws these page-side objects (three's JSON) in the arm's world (`objects`) and the scene
   * (`sceneObjects`) instead of those before, and hides the stage's own scene children at
   * `hidden`. Pictures already received are put back on their meshes.
   */
  setExtras(objects: unknown[], sceneObjects: unknown[], hidden: number[]): void {
    this.ownScene.forEach((o, i) => (o.visible = !hidden.includes(i)));
    for (const o of this.extras) {
      o.removeFromParent();
      o.traverse((c) => {
        const mesh = c as THREE.Mesh;
        mesh.geometry?.dispose();
        const m = mesh.material;
        for (const mat of Array.isArray(m) ? m : m ? [m] : []) mat.dispose();
      });
    }
    const inWorld = objects.map((json) => this.objectLoader.parse(json));
    const inScene = sceneObjects.map((json) => this.objectLoader.parse(json));
    for (const o of inWorld) this.stage.world.add(o);
    for (const o of inScene) this.scene.add(o);
    this.extras = [...inWorld, ...inScene];
    // Looking through a camera (../CameraScreens.ts puts its picture behind everything): the
    // twin goes translucent over it, as on the main thread.
    this.viewingThrough = inScene.some((o) => o.name.startsWith('camera-backdrop-'));
    this.applyTwinLook();
    for (const [uuid, texture] of this.textures) {
      const mesh = this.findExtra(uuid);
      if (mesh) attach(mesh, texture);
      else {
        texture.dispose();
        (texture.image as ImageBitmap | null)?.close?.();
        this.textures.delete(uuid);
      }
    }
    this.needsRender = this.shadowsDirty = true;
  }

  private applyTwinLook(): void {
    const robot = this.live?.robot ?? null;
    if (this.viewingThrough && robot) {
      if (this.twin.root !== robot) this.twin.apply(robot);
    } else this.twin.restore();
  }

  /** A new picture for the mesh `uuid`'s texture (a camera's frame). */
  setTexture(uuid: string, bitmap: ImageBitmap): void {
    let texture = this.textures.get(uuid);
    if (!texture) {
      texture = new THREE.Texture();
      texture.colorSpace = THREE.SRGBColorSpace;
      texture.flipY = false;
      this.textures.set(uuid, texture);
    } else (texture.image as ImageBitmap | null)?.close?.();
    texture.image = bitmap;
    texture.needsUpdate = true;
    const mesh = this.findExtra(uuid);
    if (mesh) attach(mesh, texture);
    this.needsRender = true;
  }

  private findExtra(uuid: string): THREE.Mesh | null {
    for (const root of this.extras) {
      const o = root.getObjectByProperty('uuid', uuid);
      if (o) return o as THREE.Mesh;
    }
    return null;
  }

  /** Takes what the page sent; drawn on the next frame. */
  take(m: FrameInput): void {
    const mir = this.mirror;
    if (m.arm) mir.store.opts.arm = m.arm;
    if (m.rendered) {
      mir.store.rendered = m.rendered;
      mir.renderedChanged = true;
    }
    if (m.commandedPwm) mir.store.commandedPwm = m.commandedPwm;
    if (m.target) Object.assign(mir.target, m.target);
    if (m.plan !== undefined) mir.plan = m.plan;
    if (m.sibling !== undefined) {
      mir.sibling.active = m.sibling !== null;
      mir.sibling.record = m.sibling === null ? null : true;
      if (m.sibling) mir.sibling.angles = m.sibling;
      mir.sibling.changed = true;
    }
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

  start(): void {
    if (this.running) return;
    this.running = true;
    requestAnimationFrame(this.tick);
  }

  private readonly tick = (): void => {
    if (!this.running) return;
    requestAnimationFrame(this.tick);
    const now = performance.now();
    const mir = this.mirror;
    if (mir.renderedChanged) {
      mir.renderedChanged = false;
      if (this.live?.pose(mir.store.rendered)) this.needsRender = this.shadowsDirty = true;
    }
    if (this.ghost?.update(now, this.planSource)) this.needsRender = true;
    if (this.sibling?.update(now)) this.needsRender = this.shadowsDirty = true;
    if (this.marker.update()) this.needsRender = true;
    if (this.trackingPaint?.update(this.tracking)) this.needsRender = true;
    if (this.warmupFrames > 0) {
      this.warmupFrames--;
      this.needsRender = true;
    }
    if (this.needsRender) {
      this.needsRender = false;
      this.governor.frame(now - this.lastRenderAt);
      if (this.renderer.getPixelRatio() !== this.governor.ratio)
        this.renderer.setPixelRatio(this.governor.ratio);
      this.draw();
      this.lastRenderAt = now;
      this.lastMovedAt = now;
      this.refined = false;
    } else {
      this.lastRenderAt = NaN;
      if (!this.refined && now - this.lastMovedAt >= REFINE_AFTER_MS) {
        this.refined = true;
        if (this.governor.ratio < this.maxRatio) {
          this.renderer.setPixelRatio(this.maxRatio);
          this.draw();
        }
      }
    }
  };

  private draw(): void {
    if (this.shadowsDirty) {
      this.renderer.shadowMap.needsUpdate = true;
      this.shadowsDirty = false;
    }
    this.renderer.render(this.scene, this.camera);
    this.frames++;
    const t = this.mirror.target;
    const report: Rendered = {
      type: 'rendered',
      at: performance.timeOrigin + performance.now(),
      frames: this.frames,
      sizeSeq: this.sizeSeq,
      pixelRatio: this.renderer.getPixelRatio(),
      robot: this.live?.values() ?? [],
      ghost: this.ghost?.posed.values() ?? [],
      sibling: this.sibling?.posed.values() ?? [],
      ghostShows: t.ghostShows,
      ghostPainted: this.ghost?.painted ?? '',
      trackingLevels: this.trackingPaint ? this.trackingPaint.levels.slice() : null,
    };
    this.post(report);
  }
}

/** Puts `texture` on `mesh`'s material (once; later pictures only update the texture). */
function attach(mesh: THREE.Mesh, texture: THREE.Texture): void {
  const m = mesh.material as THREE.MeshBasicMaterial | undefined;
  if (!m || m.map === texture) return;
  m.map = texture;
  m.color?.set(0xffffff);
  m.needsUpdate = true;
}
