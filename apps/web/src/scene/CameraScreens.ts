/**
 * The arm's cameras in the 3D view (issue 15): a screen at each posed camera's position, facing
 * back along its line of sight (seen the right way round from behind the camera), showing the
 * camera's picture as a texture; and "view through this camera": the 3D view takes the
 * camera's pose and vertical field of view, and the live picture is laid over the whole view
 * at half opacity, so the twin shows through it and a twin that does not match the arm is seen
 * at a glance. Plain object on the Viewer's one frame loop; textures are uploaded only when the
 * player drew a new frame, at most `TEXTURE_HZ` times a second.
 */
import * as THREE from 'three';
import type { CameraPose } from '@armtwin/camera/announcement';
import type { ArmCamera, CameraPicture } from '../cameras/CameraHub.ts';
import type { Viewer } from './Viewer.ts';

/** What the screens show: the hub's cameras and the pictures their views draw. */
export interface CameraSource {
  readonly version: number;
  readonly list: ArmCamera[];
  readonly pictures: ReadonlyMap<string, CameraPicture>;
}

/** A screen's width in the scene, m (height from the picture's aspect). */
export const SCREEN_WIDTH_M = 0.16;
/** Texture uploads per second per camera, at most (software WebGL pays for each). */
export const TEXTURE_HZ = 10;
/** Opacity of the live picture laid over the twin when viewing through a camera. */
export const OVERLAY_OPACITY = 0.5;
/** Vertical field of view when the announcement gives none, degrees. */
export const DEFAULT_FOV_DEG = 50;
/** Distance of the overlay in front of the camera, m (beyond the near plane). */
const OVERLAY_DISTANCE_M = 0.05;

interface Screen {
  camId: string;
  picture: CameraPicture | undefined;
  texture: THREE.CanvasTexture | null;
  mesh: THREE.Mesh<THREE.PlaneGeometry, THREE.MeshBasicMaterial>;
  frames: number;
  uploadedAt: number;
}

const mm = (v: readonly number[]) => new THREE.Vector3(v[0]! / 1000, v[1]! / 1000, v[2]! / 1000);

export class CameraScreens {
  private readonly screens = new Map<string, Screen>();
  private version = -1;
  /** The camera looked through, '' = the orbit view. */
  viewing = '';
  private overlay: THREE.Mesh<THREE.PlaneGeometry, THREE.MeshBasicMaterial> | null = null;
  private saved: { position: THREE.Vector3; target: THREE.Vector3; fov: number } | null = null;

  constructor(
    private readonly viewer: Viewer,
    private readonly source: CameraSource,
  ) {
    viewer.frameHooks.add(this.tick);
  }

  /** Looks through `camId` (a camera with a pose), or back to the orbit view with ''. */
  viewThrough(camId: string): void {
    if (camId === this.viewing) return;
    this.leave();
    const cam = this.source.list.find((c) => c.camId === camId);
    if (!cam?.pose) return;
    this.enter(cam.camId, cam.pose, cam.fovDeg ?? DEFAULT_FOV_DEG);
  }

  private readonly tick = (now: number): boolean => {
    let changed = false;
    if (this.version !== this.source.version) {
      this.version = this.source.version;
      this.sync();
      changed = true;
    }
    for (const s of this.screens.values()) changed = this.refresh(s, now) || changed;
    return changed;
  };

  /** Rebuilds the screens from the hub's list (a camera without a pose has none). */
  private sync(): void {
    const cams = new Map(this.source.list.filter((c) => c.pose).map((c) => [c.camId, c]));
    for (const [id, s] of this.screens)
      if (!cams.has(id)) {
        this.dropScreen(s);
        this.screens.delete(id);
      }
    for (const cam of cams.values()) {
      let s = this.screens.get(cam.camId);
      if (!s) {
        const mesh = new THREE.Mesh(
          new THREE.PlaneGeometry(SCREEN_WIDTH_M, (SCREEN_WIDTH_M * 3) / 4),
          new THREE.MeshBasicMaterial({ color: 0x000000, side: THREE.DoubleSide }),
        );
        mesh.name = `camera-screen-${cam.camId}`;
        this.viewer.world.add(mesh);
        s = {
          camId: cam.camId,
          picture: undefined,
          texture: null,
          mesh,
          frames: -1,
          uploadedAt: 0,
        };
        this.screens.set(cam.camId, s);
      }
      this.place(s.mesh, cam.pose!);
    }
    if (this.viewing && !cams.has(this.viewing)) this.leave();
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

  /** Follows the view's picture (its canvas may be replaced); uploads a new frame now and then. */
  private refresh(s: Screen, now: number): boolean {
    const picture = this.source.pictures.get(s.camId);
    if (picture !== s.picture) {
      s.picture = picture;
      s.texture?.dispose();
      s.texture = picture ? new THREE.CanvasTexture(picture.canvas) : null;
      if (s.texture) s.texture.colorSpace = THREE.SRGBColorSpace;
      s.mesh.material.map = s.texture;
      s.mesh.material.color.set(s.texture ? 0xffffff : 0x000000);
      s.mesh.material.needsUpdate = true;
      s.frames = -1;
      if (this.viewing === s.camId && this.overlay) {
        this.overlay.material.map = s.texture;
        this.overlay.material.needsUpdate = true;
      }
      return true;
    }
    if (!picture || !s.texture) return false;
    const frames = picture.frames();
    if (frames === s.frames || now - s.uploadedAt < 1000 / TEXTURE_HZ) return false;
    s.frames = frames;
    s.uploadedAt = now;
    const c = picture.canvas;
    s.mesh.scale.set(1, ((c.height / c.width) * 4) / 3, 1);
    s.texture.needsUpdate = true;
    return true;
  }

  private enter(camId: string, pose: CameraPose, fovDeg: number): void {
    const { camera, controls, world } = this.viewer;
    this.saved = {
      position: camera.position.clone(),
      target: controls.target.clone(),
      fov: camera.fov,
    };
    world.updateMatrixWorld();
    const eye = world.localToWorld(mm(pose.position));
    const look = world.localToWorld(mm(pose.lookAt));
    controls.enabled = false;
    controls.target.copy(look);
    camera.position.copy(eye);
    camera.up.set(0, 1, 0);
    camera.lookAt(look);
    camera.fov = fovDeg;
    camera.updateProjectionMatrix();
    const screen = this.screens.get(camId);
    if (screen) screen.mesh.visible = false;
    // The live picture over the whole view at the camera's own field of view and aspect.
    const h = 2 * OVERLAY_DISTANCE_M * Math.tan(THREE.MathUtils.degToRad(fovDeg) / 2);
    const c = screen?.picture?.canvas;
    const aspect = c && c.height > 0 ? c.width / c.height : 4 / 3;
    const overlay = new THREE.Mesh(
      new THREE.PlaneGeometry(h * aspect, h),
      new THREE.MeshBasicMaterial({
        map: screen?.texture ?? null,
        transparent: true,
        opacity: OVERLAY_OPACITY,
        depthTest: false,
        depthWrite: false,
      }),
    );
    overlay.renderOrder = 1000;
    overlay.position
      .copy(eye)
      .add(look.clone().sub(eye).normalize().multiplyScalar(OVERLAY_DISTANCE_M));
    overlay.quaternion.copy(camera.quaternion);
    overlay.name = `camera-overlay-${camId}`;
    this.viewer.scene.add(overlay);
    this.overlay = overlay;
    this.viewing = camId;
    this.viewer.invalidate();
  }

  private leave(): void {
    if (!this.viewing) return;
    const { camera, controls } = this.viewer;
    if (this.overlay) {
      this.viewer.scene.remove(this.overlay);
      this.overlay.geometry.dispose();
      this.overlay.material.dispose();
      this.overlay = null;
    }
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
