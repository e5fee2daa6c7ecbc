/**
 * Loads the arm's URDF with urdf-loader and its meshes (STL, OBJ, DAE: `meshLoaders.ts`) with an
 * injected mesh loader, and resolves when every mesh is in or has failed, so the first frame
 * shows the whole arm. `package://<pkg>/<path>` is `<path>` in the model folder (the folder
 * stands for every package); a relative path is relative to the URDF. A missing URDF rejects
 * with a message naming the file; a bad mesh does not: it is left out of the arm and listed in
 * `failures`, and the rest of the arm loads. Meshes are fetched once and shared by every robot
 * built from them (the live arm and the ghost).
 */
import * as THREE from 'three';
import URDFLoader, { type URDFRobot } from 'urdf-loader';
import { fetchMesh, OWN_MATERIALS } from './meshLoaders.ts';

export type MaterialFactory = (urdfMaterial: THREE.Material) => THREE.Material;

/** A mesh that could not be loaded: its URL and why. */
export interface MeshFailure {
  url: string;
  message: string;
}

export interface BuiltRobot {
  robot: URDFRobot;
  /** The meshes left out, each once. */
  failures: MeshFailure[];
}

export class RobotModelLoader {
  private readonly meshes = new Map<string, Promise<THREE.Object3D>>();
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

  private mesh(url: string): Promise<THREE.Object3D> {
    let m = this.meshes.get(url);
    if (!m) {
      m = fetchMesh(url);
      this.meshes.set(url, m);
    }
    return m;
  }

  /** A robot with every visual mesh that could be loaded, its materials made by `makeMaterial`. */
  async build(makeMaterial: MaterialFactory): Promise<BuiltRobot> {
    const text = await this.fetchText();
    const pending: Promise<void>[] = [];
    const failures: MeshFailure[] = [];
    const loader = new URDFLoader();
    loader.parseCollision = false;
    loader.workingPath = this.baseUrl;
    loader.packages = () => this.baseUrl.replace(/\/$/, '');
    loader.loadMeshCb = (url, _manager, material, onLoad) => {
      pending.push(
        this.mesh(url).then(
          (template) => onLoad(dress(template.clone(), material, makeMaterial)),
          (err: unknown) => {
            const message = err instanceof Error ? err.message : String(err);
            if (!failures.some((f) => f.url === url)) failures.push({ url, message });
          },
        ),
      );
    };
    const robot = loader.parse(text);
    if (!robot || Object.keys(robot.joints).length === 0)
      throw new Error(`${this.urdfUrl}: no joints`);
    await Promise.all(pending);
    return { robot, failures };
  }
}

/**
 * Gives every mesh of a loaded object a material from `makeMaterial`: the file's own colours for
 * a DAE, the URDF's `<material>` otherwise (STL has none; an OBJ's .mtl is not read). Geometry stays shared with the cached template.
 */
function dress(
  obj: THREE.Object3D,
  urdfMaterial: THREE.Material,
  makeMaterial: MaterialFactory,
): THREE.Object3D {
  obj.traverse((child) => {
    if (!(child instanceof THREE.Mesh)) return;
    const own = (Array.isArray(child.material) ? child.material[0] : child.material) as
      THREE.Material | undefined;
    const fromFile = obj.userData[OWN_MATERIALS] === true && own && 'color' in own;
    child.material = makeMaterial(fromFile ? own : urdfMaterial);
    child.castShadow = true;
    child.receiveShadow = true;
  });
  return obj;
}

/** The live arm's look: the URDF colour on a lightly metallic surface. */
export const solidMaterial: MaterialFactory = (m) =>
  new THREE.MeshStandardMaterial({
    color: (m as THREE.MeshPhongMaterial).color ?? new THREE.Color(0.7, 0.7, 0.7),
    roughness: 0.55,
    metalness: 0.15,
  });
