/**
 * Mesh files for urdf-loader's injected `loadMeshCb`: STL (ASCII and binary), OBJ and COLLADA
 * (DAE), each parsed by three.js's own loader after a fetch that checks the HTTP status, so a
 * missing file says "HTTP 404" instead of a parser failing on the HUD's HTML.
 */
import * as THREE from 'three';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';

/** The mesh formats the HUD reads, by file extension. */
export const MESH_KINDS = ['stl', 'obj', 'dae'] as const;
export type MeshKind = (typeof MESH_KINDS)[number];

/** The format of a mesh file by its extension (query and fragment ignored), or null. */
export function meshKind(url: string): MeshKind | null {
  const ext = /\.([a-z0-9]+)(?:[?#].*)?$/i.exec(url)?.[1]?.toLowerCase();
  return (MESH_KINDS as readonly string[]).includes(ext ?? '') ? (ext as MeshKind) : null;
}

/** `userData` key set on a parsed DAE: its materials are the file's own, to be kept. */
export const OWN_MATERIALS = 'armtwinOwnMaterials';

/** Parses a mesh file's bytes; the result's own transform is left to urdf-loader. */
export function parseMesh(kind: MeshKind, data: ArrayBuffer, url: string): THREE.Object3D {
  switch (kind) {
    case 'stl': {
      const geometry = new STLLoader().parse(data);
      if (!geometry.getAttribute('position')?.count) throw new Error('no triangles');
      return withNormals(new THREE.Mesh(geometry));
    }
    case 'obj':
      return withNormals(new OBJLoader().parse(new TextDecoder().decode(data)));
    case 'dae': {
      const dae = new ColladaLoader().parse(
        new TextDecoder().decode(data),
        THREE.LoaderUtils.extractUrlBase(url),
      );
      if (!dae?.scene) throw new Error('not a COLLADA file');
      dae.scene.userData[OWN_MATERIALS] = true;
      return dae.scene;
    }
    default: {
      const never: never = kind;
      throw new Error(`unknown mesh kind ${String(never)}`);
    }
  }
}

/**
 * Computes face normals where a file has none or only zeros (many exporters write `facet normal
 * 0 0 0` in STL; OBJ may omit `vn`), else the lit material draws the mesh black.
 */
function withNormals(obj: THREE.Object3D): THREE.Object3D {
  obj.traverse((child) => {
    if (!(child instanceof THREE.Mesh)) return;
    const g = child.geometry as THREE.BufferGeometry;
    const n = g.getAttribute('normal');
    let zero = true;
    for (let i = 0; n && zero && i < n.count; i++) zero = !(n.getX(i) || n.getY(i) || n.getZ(i));
    if (zero) g.computeVertexNormals();
  });
  return obj;
}

/** Fetches and parses one mesh file; rejects with a message naming the file. */
export async function fetchMesh(url: string): Promise<THREE.Object3D> {
  const kind = meshKind(url);
  if (!kind) throw new Error(`${url}: unsupported mesh format (STL, OBJ or DAE)`);
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: HTTP ${res.status}`);
  try {
    return parseMesh(kind, await res.arrayBuffer(), url);
  } catch (err) {
    throw new Error(`${url}: ${err instanceof Error ? err.message : String(err)}`, { cause: err });
  }
}
