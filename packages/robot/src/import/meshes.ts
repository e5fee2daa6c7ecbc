/**
 * The meshes a URDF references: finding them (`<mesh filename="…">` in visuals and collisions),
 * resolving `package://` and relative paths in the source tree, rewriting them, and sizing them
 * (bytes and triangles) so that meshes too large for a page are warned about.
 */
import type { Element } from '@xmldom/xmldom';
import { attribute, childElements, parseUrdfXml, serializeUrdf } from '../urdf/urdf-xml.ts';
import { ancestors, basename, dirname, join, normalize } from './paths.ts';

/** The formats the HUD reads (apps/web/src/scene/meshLoaders.ts), by extension. */
export const IMPORT_MESH_KINDS = ['stl', 'obj', 'dae'] as const;
export type ImportMeshKind = (typeof IMPORT_MESH_KINDS)[number];

export interface MeshRef {
  /** `filename` as written in the URDF. */
  filename: string;
  /** Whether it is in a `<visual>` (the HUD draws those) rather than only a `<collision>`. */
  visual: boolean;
  /** The link it belongs to. */
  link: string;
}

/** The `<mesh>` elements of the robot's own links' visuals and collisions. */
function meshElements(robot: Element): { mesh: Element; link: string; visual: boolean }[] {
  return childElements(robot, 'link').flatMap((link) =>
    (['visual', 'collision'] as const).flatMap((kind) =>
      childElements(link, kind).flatMap((block) =>
        childElements(block, 'geometry').flatMap((g) =>
          childElements(g, 'mesh').map((mesh) => ({
            mesh,
            link: attribute(link, 'name') ?? '',
            visual: kind === 'visual',
          })),
        ),
      ),
    ),
  );
}

/**
 * Every `<mesh filename>` of the robot's links, with its link and whether a visual uses it;
 * one entry per filename. Text that is not a URDF has none (the profile's reader reports why).
 */
export function meshRefs(urdf: string): MeshRef[] {
  const parsed = parseUrdfXml(urdf);
  if (!parsed.ok) return [];
  const byName = new Map<string, MeshRef>();
  for (const { mesh, link, visual } of meshElements(parsed.robot)) {
    const filename = attribute(mesh, 'filename');
    if (filename === undefined) continue;
    const prev = byName.get(filename);
    if (prev) prev.visual ||= visual;
    else byName.set(filename, { filename, visual, link });
  }
  return [...byName.values()];
}

/** The mesh format of a file name, or null when the HUD cannot read it. */
export function importMeshKind(file: string): ImportMeshKind | null {
  const ext = /\.([a-z0-9]+)$/i.exec(file)?.[1]?.toLowerCase() ?? '';
  return (IMPORT_MESH_KINDS as readonly string[]).includes(ext) ? (ext as ImportMeshKind) : null;
}

/**
 * Where a mesh `filename` is in the source tree, or null. `package://<pkg>/<rel>`: in the
 * nearest ancestor of the URDF's folder named `<pkg>` or holding a `<pkg>` folder, else in the
 * nearest ancestor that holds `<rel>` (a ROS package's root is usually one or two levels above
 * its `urdf/` folder, and package names often differ from folder names). `file://` paths are
 * taken as they are; anything else is relative to the URDF's folder.
 */
export function resolveMeshPath(
  filename: string,
  urdfPath: string,
  has: (path: string) => boolean,
): string | null {
  const urdfDir = dirname(urdfPath);
  const pkg = /^package:\/\/([^/]+)\/(.+)$/.exec(filename);
  if (pkg) {
    const [, name, rel] = pkg as unknown as [string, string, string];
    const dirs = ancestors(urdfDir);
    for (const d of dirs) {
      if (basename(d) === name && has(join(d, rel))) return join(d, rel);
      if (has(join(d, name, rel))) return join(d, name, rel);
    }
    for (const d of dirs) if (has(join(d, rel))) return join(d, rel);
    return null;
  }
  if (filename.startsWith('file://')) {
    const p = normalize(decodeURI(filename.slice('file://'.length)));
    return has(p) ? p : null;
  }
  if (/^[a-z][a-z0-9+.-]*:\/\//i.test(filename)) return null;
  const p = filename.startsWith('/') ? normalize(filename) : join(urdfDir, filename);
  return has(p) ? p : null;
}

/**
 * Replaces each link mesh's `filename` by `rename(filename)` (unchanged where it gives null);
 * the text comes back re-serialised, or as it was when nothing changed or it is not a URDF.
 */
export function rewriteMeshPaths(
  urdf: string,
  rename: (filename: string) => string | null,
): string {
  const parsed = parseUrdfXml(urdf);
  if (!parsed.ok) return urdf;
  let changed = false;
  for (const { mesh } of meshElements(parsed.robot)) {
    const name = attribute(mesh, 'filename');
    const next = name === undefined ? null : rename(name);
    if (next === null || next === name) continue;
    mesh.setAttribute('filename', next);
    changed = true;
  }
  return changed ? serializeUrdf(parsed.doc) : urdf;
}

/** Triangles in a mesh file (DAE: the counts its primitives declare), or NaN when unreadable. */
export function meshTriangles(kind: ImportMeshKind, bytes: Uint8Array): number {
  switch (kind) {
    case 'stl': {
      if (bytes.length >= 84) {
        const n = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength).getUint32(
          80,
          true,
        );
        if (84 + 50 * n === bytes.length) return n;
      }
      const text = new TextDecoder().decode(bytes.subarray(0, Math.min(bytes.length, 512)));
      if (!/^\s*solid\b/.test(text)) return NaN;
      return (new TextDecoder().decode(bytes).match(/\bfacet\s+normal\b/g) ?? []).length;
    }
    case 'obj': {
      let n = 0;
      for (const line of new TextDecoder().decode(bytes).split('\n')) {
        if (!line.startsWith('f ')) continue;
        n += Math.max(0, line.trim().split(/\s+/).length - 3);
      }
      return n;
    }
    case 'dae': {
      const text = new TextDecoder().decode(bytes);
      if (!/<COLLADA\b/.test(text)) return NaN;
      let n = 0;
      for (const m of text.matchAll(
        /<(triangles|polylist|polygons)\b[^>]*?count\s*=\s*["'](\d+)["']/g,
      ))
        n += Number(m[2]);
      return n;
    }
    default: {
      const never: never = kind;
      return never;
    }
  }
}
