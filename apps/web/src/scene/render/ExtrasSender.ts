/**
 * Sends the render worker what the page's other parts added to the 3D view (the waypoint
 * spheres and path, the cameras' screens, a camera's picture while viewing through) and the
 * cameras' pictures, each only when it changed. The worker's side: ./WorkerExtras.ts.
 */
import type * as THREE from 'three';
import type { ToWorker } from './messages.ts';

export class ExtrasSender {
  /** The world's own children (the stage's): anything else was added by another part. */
  private readonly ownChildren: Set<THREE.Object3D>;
  /** The stage's own scene children (floor, grid, lights), in the worker's order too. */
  private readonly ownScene: THREE.Object3D[];
  /** The extras' JSON as last sent (sent again only when it changed). */
  private lastExtras = '';
  /** The extras' textured meshes (uuid → texture), and the picture last sent for each. */
  private readonly textured = new Map<string, THREE.Texture>();
  private readonly sentPictures = new Map<string, string>();

  /** Call right after the stage is built: what `scene` and `world` hold now is the stage's own. */
  constructor(
    private readonly scene: THREE.Scene,
    private readonly world: THREE.Group,
    private readonly send: (m: ToWorker, transfer?: Transferable[]) => void,
  ) {
    this.ownChildren = new Set(world.children);
    this.ownScene = [...scene.children];
  }

  /**
   * Sends the objects other parts added to the world or to the scene, and which of the stage's
   * own objects they hid, when that changed. Textures go separately (`sendPictures`): the JSON
   * carries none.
   */
  sync(): void {
    this.textured.clear();
    const toJson = (o: THREE.Object3D): unknown => withoutMaps(o, this.textured);
    const objects = this.world.children.filter((o) => !this.ownChildren.has(o)).map(toJson);
    const sceneObjects = this.scene.children
      .filter((o) => o !== this.world && !this.ownScene.includes(o))
      .map(toJson);
    const hidden = this.ownScene.flatMap((o, i) => (o.visible ? [] : [i]));
    const json = JSON.stringify([objects, sceneObjects, hidden]);
    if (json === this.lastExtras) return;
    this.lastExtras = json;
    this.send({ type: 'extras', objects, sceneObjects, hidden });
    this.sentPictures.clear(); // the meshes are new there: their pictures go again
  }

  /** Sends each textured extra's picture when it changed (a camera's new frame). */
  sendPictures(): void {
    for (const [uuid, texture] of this.textured) {
      const image = texture.image as CanvasImageSource | null;
      const key = `${texture.uuid}:${texture.version}`;
      if (!image || this.sentPictures.get(uuid) === key) continue;
      this.sentPictures.set(uuid, key);
      createImageBitmap(image as ImageBitmapSource, { imageOrientation: 'flipY' }).then(
        (bitmap) => this.send({ type: 'texture', uuid, bitmap }, [bitmap]),
        () => this.sentPictures.delete(uuid), // an empty canvas: tried again next frame
      );
    }
  }
}

/**
 * `o.toJSON()` without texture maps (a camera's picture would go as a data URL each time):
 * each mesh with a map is noted in `textured` (mesh uuid → texture) and keeps its map.
 */
function withoutMaps(o: THREE.Object3D, textured: Map<string, THREE.Texture>): unknown {
  const taken: [THREE.MeshBasicMaterial, THREE.Texture][] = [];
  o.traverse((c) => {
    const m = (c as THREE.Mesh).material as THREE.MeshBasicMaterial | undefined;
    if (m && !Array.isArray(m) && m.map) {
      textured.set(c.uuid, m.map);
      taken.push([m, m.map]);
      m.map = null;
    }
  });
  try {
    return o.toJSON();
  } finally {
    for (const [m, map] of taken) m.map = map;
  }
}
