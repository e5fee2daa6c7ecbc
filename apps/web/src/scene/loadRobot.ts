/**
 * Loads the arm's URDF with urdf-loader and its STL meshes with an injected mesh loader
 * (three's STLLoader), and resolves only when every mesh is in, so the first frame shows the
 * whole arm. A missing URDF or mesh rejects with a message naming the file. Meshes are fetched
 * once and shared by every robot built from them (the live arm and the ghost).
 */
import * as THREE from 'three';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import URDFLoader, { type URDFRobot } from 'urdf-loader';

export type MaterialFactory = (urdfMaterial: THREE.Material) => THREE.Material;

export class RobotModelLoader {
  private readonly geometries = new Map<string, Promise<THREE.BufferGeometry>>();
  private text: Promise<string> | null = null;
  private readonly baseUrl: string;

  constructor(readonly urdfUrl: string) {
    this.baseUrl = THREE.LoaderUtils.extractUrlBase(urdfUrl);
  }

  private fetchText(): Promise<string> {
    this.text ??= fetch(this.urdfUrl).then(async (res) => {
      if (!res.ok)
        throw new Error(`could not load the arm model ${this.urdfUrl}: HTTP ${res.status}`);
      const body = await res.text();
      if (!body.includes('<robot')) throw new Error(`${this.urdfUrl} is not a URDF file`);
      return body;
    });
    return this.text;
  }

  private geometry(url: string): Promise<THREE.BufferGeometry> {
    let g = this.geometries.get(url);
    if (!g) {
      g = new STLLoader().loadAsync(url).catch((err: unknown) => {
        throw new Error(
          `could not load mesh ${url}: ${err instanceof Error ? err.message : String(err)}`,
        );
      });
      this.geometries.set(url, g);
    }
    return g;
  }

  /** A robot whose every visual mesh has loaded, its materials made by `makeMaterial`. */
  async build(makeMaterial: MaterialFactory): Promise<URDFRobot> {
    const text = await this.fetchText();
    const pending: Promise<void>[] = [];
    const loader = new URDFLoader();
    loader.parseCollision = false;
    loader.workingPath = this.baseUrl;
    loader.loadMeshCb = (url, _manager, material, onLoad) => {
      pending.push(
        this.geometry(url).then((geometry) => {
          const mesh = new THREE.Mesh(geometry, makeMaterial(material));
          mesh.castShadow = true;
          mesh.receiveShadow = true;
          onLoad(mesh);
        }),
      );
    };
    const robot = loader.parse(text);
    if (!robot || Object.keys(robot.joints).length === 0)
      throw new Error(`${this.urdfUrl}: no joints`);
    await Promise.all(pending);
    return robot;
  }
}

/** The live arm's look: the URDF colour on a lightly metallic surface. */
export const solidMaterial: MaterialFactory = (m) =>
  new THREE.MeshStandardMaterial({
    color: (m as THREE.MeshPhongMaterial).color ?? new THREE.Color(0.7, 0.7, 0.7),
    roughness: 0.55,
    metalness: 0.15,
  });
