/**
 * The arm's cameras in the 3D view (issue 15): a screen at each posed camera's position, facing
 * back along its line of sight (seen the right way round from behind the camera), showing the
 * camera's picture as a texture; and "view through this camera": the 3D view takes the
 * camera's pose (its calibration, else its announcement) and vertical field of view, the live
 * picture fills the view behind everything, opaque, with the camera's own aspect, the floor and
 * grid step aside, and the twin is drawn translucent over the picture (the scene runtime does
 * that when it is told a camera is looked through: ./render/SceneRuntime.ts, ./TranslucentTwin.ts),
 * so a twin that does not match the arm is seen at a glance; the ghost and the other overlays
 * draw as ever. Leaving puts everything back as it was. While calibrating by eye the view
 * follows a draft placement (`preview`). Plain object on the 3D view's one frame loop; it tells
 * the decoders which cameras are shown (screens in view, the one looked through); textures are
 * uploaded only when the player drew a new frame, at most `TEXTURE_HZ` times a second.
 */
import * as THREE from 'three';
import type { CameraPose } from '@armtwin/camera/client';
import { placementOf, type ArmCamera, type CameraPlacement } from '../core/cameras/CameraHub.ts';
import type { CameraDecoders } from '../core/cameras/CameraDecoders.ts';
import { twinPoints, type TwinPoint } from './twinPoints.ts';
import type { SceneView } from './SceneView.ts';

/** What the screens show: the hub's cameras (with their calibrations). */
export interface CameraSource {
  readonly version: number;
  readonly list: ArmCamera[];
}

/** A screen's width in the scene, m (height from the picture's aspect). */
export const SCREEN_WIDTH_M = 0.16;
/** Texture uploads per second per camera, at most (software WebGL pays for each). */
export const TEXTURE_HZ = 10;
/** Distance of the live picture in front of the camera, m (beyond the near plane). */
const BACKDROP_DISTANCE_M = 0.05;

interface Screen {
  camId: string;
  texture: THREE.CanvasTexture | null;
  canvas: HTMLCanvasElement | null;
  mesh: THREE.Mesh<THREE.PlaneGeometry, THREE.MeshBasicMaterial>;
  frames: number;
  uploadedAt: number;
}

const mm = (v: readonly number[]) => new THREE.Vector3(v[0]! / 1000, v[1]! / 1000, v[2]! / 1000);
const frustum = new THREE.Frustum();
const viewProjection = new THREE.Matrix4();

export class CameraScreens {
  private readonly screens = new Map<string, Screen>();
  private version = -1;
  /** The camera looked through, '' = the orbit view. */
  viewing = '';
  /** The placement the view shows while calibrating by eye (null: the camera's own). */
  private draft: CameraPlacement | null = null;
  /** The live picture behind everything while viewing through. */
  private backdrop: THREE.Mesh<THREE.PlaneGeometry, THREE.MeshBasicMaterial> | null = null;
  /** The live arm the view was last placed for (a new model frames the orbit camera anew). */
  private followed: object | null = null;
  /** Scene objects hidden while viewing through (floor, grid, …), to show again on leaving. */
  private hidden: THREE.Object3D[] = [];
  private saved: { position: THREE.Vector3; target: THREE.Vector3; fov: number } | null = null;
  private readonly inView = new Set<string>();

  constructor(
    private readonly viewer: SceneView,
    private readonly source: CameraSource,
    private readonly decoders: CameraDecoders,
  ) {
    viewer.frameHooks.add(this.tick);
  }

  /** Looks through `camId` (a camera with a pose), or back to the orbit view with ''. */
  viewThrough(camId: string): void {
    if (camId === this.viewing) return;
    this.leave();
    const cam = this.source.list.find((c) => c.camId === camId);
    const placement = cam ? placementOf(cam) : null;
    if (!placement) return;
    this.enter(camId, placement);
  }

  /** Shows `placement` instead of the camera's own while viewing through (null: its own). */
  preview(placement: CameraPlacement | null): void {
    this.draft = placement;
    this.applyPlacement();
  }

  /** The twin's points a user can click in a camera's picture (four-point calibration). */
  twinPoints(): TwinPoint[] {
    return twinPoints(this.viewer.liveRobot, this.viewer.world);
  }

  private readonly tick = (now: number): boolean => {
    let changed = false;
    this.decoders.update();
    if (this.version !== this.source.version) {
      this.version = this.source.version;
      this.sync();
      changed = true;
    }
    for (const s of this.screens.values()) changed = this.refresh(s, now) || changed;
    if (this.viewing) changed = this.followViewed() || changed;
    this.tellDecoders();
    return changed;
  };

  /** Which screens are in the view's frustum: those cameras are shown, so they play. */
  private tellDecoders(): void {
    const camera = this.viewer.camera;
    camera.updateMatrixWorld();
    viewProjection.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    frustum.setFromProjectionMatrix(viewProjection);
    this.inView.clear();
    for (const s of this.screens.values())
      if (s.mesh.visible && frustum.intersectsObject(s.mesh)) this.inView.add(s.camId);
    this.decoders.setScene(this.inView, this.viewing);
  }

  /** Rebuilds the screens from the hub's list (a camera without a pose has none). */
  private sync(): void {
    const placed = new Map<string, CameraPlacement>();
    for (const c of this.source.list) {
      const p = placementOf(c);
      if (p) placed.set(c.camId, p);
    }
    for (const [id, s] of this.screens)
      if (!placed.has(id)) {
        this.dropScreen(s);
        this.screens.delete(id);
      }
    for (const [camId, p] of placed) {
      let s = this.screens.get(camId);
      if (!s) {
        const mesh = new THREE.Mesh(
          new THREE.PlaneGeometry(SCREEN_WIDTH_M, (SCREEN_WIDTH_M * 3) / 4),
          new THREE.MeshBasicMaterial({ color: 0x000000, side: THREE.DoubleSide }),
        );
        mesh.name = `camera-screen-${camId}`;
        this.viewer.world.add(mesh);
        s = { camId, texture: null, canvas: null, mesh, frames: -1, uploadedAt: 0 };
        this.screens.set(camId, s);
      }
      this.place(s.mesh, p.pose);
      s.mesh.visible = camId !== this.viewing;
    }
    if (this.viewing && !placed.has(this.viewing)) this.leave();
    else if (this.viewing) this.applyPlacement();
  }

  /** At the camera's position, its front facing back along the line of sight. */
  private place(mesh: THREE.Object3D, pose: CameraPose): void {
    const world = this.viewer.world;
    world.updateMatrixWorld();
    const at = mm(pose.position);
    mesh.position.copy(at);
    const behind = at.clone().multiplyScalar(2).sub(mm(pose.lookAt));
    mesh.lookAt(world.localToWorld(behind));
  }

  /** Follows the camera's canvas; uploads a new frame now and then. */
  private refresh(s: Screen, now: number): boolean {
    const picture = this.decoders.pictures.get(s.camId);
    const canvas = picture?.canvas ?? null;
    if (canvas !== s.canvas) {
      s.canvas = canvas;
      s.texture?.dispose();
      s.texture = canvas ? new THREE.CanvasTexture(canvas) : null;
      if (s.texture) s.texture.colorSpace = THREE.SRGBColorSpace;
      s.mesh.material.map = s.texture;
      s.mesh.material.color.set(s.texture ? 0xffffff : 0x000000);
      s.mesh.material.needsUpdate = true;
      s.frames = -1;
      if (this.viewing === s.camId && this.backdrop) {
        this.backdrop.material.map = s.texture;
        this.backdrop.material.needsUpdate = true;
      }
      return true;
    }
    if (!picture || !s.texture || !canvas) return false;
    const frames = picture.frames();
    if (frames === s.frames || now - s.uploadedAt < 1000 / TEXTURE_HZ) return false;
    s.frames = frames;
    s.uploadedAt = now;
    s.mesh.scale.set(1, ((canvas.height / canvas.width) * 4) / 3, 1);
    s.texture.needsUpdate = true;
    if (this.viewing === s.camId) this.fitBackdrop();
    return true;
  }

  /**
   * Keeps the view at the camera when another model loads while viewing through (loading frames
   * the orbit camera on the new model).
   */
  private followViewed(): boolean {
    const robot = this.viewer.liveRobot;
    if (!robot || robot === this.followed) return false;
    this.followed = robot;
    this.applyPlacement();
    return true;
  }

  private enter(camId: string, placement: CameraPlacement): void {
    const { camera, controls, scene } = this.viewer;
    this.saved = {
      position: camera.position.clone(),
      target: controls.target.clone(),
      fov: camera.fov,
    };
    controls.enabled = false;
    this.viewing = camId;
    this.draft = null;
    const screen = this.screens.get(camId);
    if (screen) screen.mesh.visible = false;
    // The floor, its shadow and the grids would cover the picture: they step aside.
    this.hidden = scene.children.filter(
      (o) => o.visible && o !== this.viewer.world && !(o as THREE.Light).isLight,
    );
    for (const o of this.hidden) o.visible = false;
    const backdrop = new THREE.Mesh(
      new THREE.PlaneGeometry(1, 1),
      new THREE.MeshBasicMaterial({
        map: screen?.texture ?? null,
        color: screen?.texture ? 0xffffff : 0x000000,
        depthTest: false,
        depthWrite: false,
        fog: false,
        toneMapped: false,
      }),
    );
    // Drawn first, opaque, writing no depth: everything else draws over it.
    backdrop.renderOrder = -1000;
    backdrop.frustumCulled = false;
    backdrop.name = `camera-backdrop-${camId}`;
    scene.add(backdrop);
    this.backdrop = backdrop;
    this.followed = this.viewer.liveRobot;
    this.applyPlacement(placement);
  }

  /** Puts the view's camera (and the picture behind it) at the viewed camera's placement. */
  private applyPlacement(
    placement: CameraPlacement | null = this.draft ?? this.viewedPlacement(),
  ): void {
    if (!this.viewing || !placement) return;
    const { camera, controls, world } = this.viewer;
    world.updateMatrixWorld();
    const eye = world.localToWorld(mm(placement.pose.position));
    const look = world.localToWorld(mm(placement.pose.lookAt));
    controls.target.copy(look);
    camera.position.copy(eye);
    camera.up.set(0, 1, 0);
    camera.lookAt(look);
    camera.fov = placement.fovDeg;
    camera.updateProjectionMatrix();
    this.fitBackdrop();
    this.viewer.invalidate();
  }

  private viewedPlacement(): CameraPlacement | null {
    const cam = this.source.list.find((c) => c.camId === this.viewing);
    return cam ? placementOf(cam) : null;
  }

  /** The picture exactly fills the camera's field of view, at its own aspect, centred. */
  private fitBackdrop(): void {
    const b = this.backdrop;
    if (!b) return;
    const { camera } = this.viewer;
    const h = 2 * BACKDROP_DISTANCE_M * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
    const c = this.screens.get(this.viewing)?.canvas;
    const aspect = c && c.height > 0 ? c.width / c.height : 4 / 3;
    b.scale.set(h * aspect, h, 1);
    camera.getWorldDirection(b.position).multiplyScalar(BACKDROP_DISTANCE_M).add(camera.position);
    b.quaternion.copy(camera.quaternion);
  }

  private leave(): void {
    if (!this.viewing) return;
    const { camera, controls } = this.viewer;
    if (this.backdrop) {
      this.backdrop.removeFromParent();
      this.backdrop.geometry.dispose();
      this.backdrop.material.dispose();
      this.backdrop = null;
    }
    this.followed = null;
    for (const o of this.hidden) o.visible = true;
    this.hidden = [];
    const screen = this.screens.get(this.viewing);
    if (screen) screen.mesh.visible = true;
    if (this.saved) {
      camera.position.copy(this.saved.position);
      camera.fov = this.saved.fov;
      camera.updateProjectionMatrix();
      controls.target.copy(this.saved.target);
      controls.update();
    }
    controls.enabled = true;
    this.saved = null;
    this.draft = null;
    this.viewing = '';
    this.viewer.invalidate();
  }

  private dropScreen(s: Screen): void {
    if (this.viewing === s.camId) this.leave();
    s.mesh.removeFromParent();
    s.mesh.geometry.dispose();
    s.mesh.material.dispose();
    s.texture?.dispose();
  }
}
