/**
 * The live twin drawn translucent while the 3D view looks through a camera (./CameraScreens.ts),
 * so the live picture behind it shows through: each mesh gets a translucent copy of its own
 * material (writing depth, so the arm's nearer parts hide its farther ones, as on the picture);
 * `restore` puts every original material back on its mesh and disposes the copies.
 */
import * as THREE from 'three';

/** How opaque the twin is over the live picture. */
export const TWIN_OPACITY = 0.5;

type AnyMaterial = THREE.Material | THREE.Material[];

function translucent(m: THREE.Material, opacity: number): THREE.Material {
  const c = m.clone();
  c.transparent = true;
  c.opacity = m.opacity * opacity;
  c.depthWrite = true;
  return c;
}

export class TranslucentTwin {
  private readonly originals = new Map<THREE.Mesh, AnyMaterial>();
  private copies: THREE.Material[] = [];
  /** The model made translucent, null when none is. */
  root: THREE.Object3D | null = null;

  /** Makes `root`'s meshes translucent (the previous model's are restored first). */
  apply(root: THREE.Object3D, opacity = TWIN_OPACITY): void {
    this.restore();
    this.root = root;
    const made = new Map<THREE.Material, THREE.Material>();
    const copy = (m: THREE.Material) => {
      let c = made.get(m);
      if (!c) {
        c = translucent(m, opacity);
        made.set(m, c);
      }
      return c;
    };
    root.traverse((o) => {
      const mesh = o as THREE.Mesh;
      if (!mesh.isMesh) return;
      this.originals.set(mesh, mesh.material);
      mesh.material = Array.isArray(mesh.material) ? mesh.material.map(copy) : copy(mesh.material);
    });
    this.copies = [...made.values()];
  }

  /** Puts back exactly the materials `apply` found. */
  restore(): void {
    for (const [mesh, material] of this.originals) mesh.material = material;
    this.originals.clear();
    for (const c of this.copies) c.dispose();
    this.copies = [];
    this.root = null;
  }
}
