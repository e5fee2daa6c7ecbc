/**
 * What the page's other parts added to the 3D view, as the render worker draws it: the page's
 * objects (three's JSON: the waypoint spheres and path, the cameras' screens, a camera's picture
 * while viewing through) put in the arm's world or the scene in place of those before, the
 * stage's own scene children hidden where the page hid them, and the cameras' pictures (sent
 * separately, as ImageBitmaps) put back on their meshes.
 */
import * as THREE from 'three';

export class WorkerExtras {
  private readonly objectLoader = new THREE.ObjectLoader();
  private extras: THREE.Object3D[] = [];
  /** The cameras' pictures, by the uuid of the mesh they go on. */
  private readonly textures = new Map<string, THREE.Texture>();
  /** The stage's own scene children (floor, grid, lights), in the page's order. */
  private readonly ownScene: THREE.Object3D[];

  constructor(
    private readonly scene: THREE.Scene,
    private readonly world: THREE.Object3D,
  ) {
    this.ownScene = [...scene.children];
  }

  /**
   * Draws these page-side objects in the arm's world (`objects`) and the scene (`sceneObjects`)
   * instead of those before, and hides the stage's own scene children at `hidden`. Pictures
   * already received are put back on their meshes. Returns whether the view now looks through
   * a camera (../CameraScreens.ts puts its picture behind everything).
   */
  set(objects: unknown[], sceneObjects: unknown[], hidden: number[]): boolean {
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
    for (const o of inWorld) this.world.add(o);
    for (const o of inScene) this.scene.add(o);
    this.extras = [...inWorld, ...inScene];
    for (const [uuid, texture] of this.textures) {
      const mesh = this.find(uuid);
      if (mesh) attach(mesh, texture);
      else {
        texture.dispose();
        (texture.image as ImageBitmap | null)?.close?.();
        this.textures.delete(uuid);
      }
    }
    return inScene.some((o) => o.name.startsWith('camera-backdrop-'));
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
    const mesh = this.find(uuid);
    if (mesh) attach(mesh, texture);
  }

  private find(uuid: string): THREE.Mesh | null {
    for (const root of this.extras) {
      const o = root.getObjectByProperty('uuid', uuid);
      if (o) return o as THREE.Mesh;
    }
    return null;
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
