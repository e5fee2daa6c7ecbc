/**
 * `armtwin robot import`'s pure core: from a source tree holding a URDF (read through `has` and
 * `read`, so a folder, a zip or a test's map serve alike), the files of the robot folder to
 * write: `<name>.urdf` with every mesh path rewritten relative to it, the meshes under
 * `meshes/`, and `profile.json` (`deriveProfile`). Refuses, with every reason, what it cannot
 * use: no movable joint, a visual mesh that is missing or in a format the HUD cannot read.
 */
import { deriveProfile, profileNameFrom, type DerivedProfile } from './derive-profile.ts';
import {
  importMeshKind,
  meshRefs,
  meshTriangles,
  resolveMeshPath,
  rewriteMeshPaths,
} from './meshes.ts';
import { attribute, parseUrdfXml } from '../urdf/urdf-xml.ts';
import { commonDir, inside } from './paths.ts';

export interface ImportSource {
  /** The URDF's path in the tree ('/'-separated). */
  urdfPath: string;
  urdfText: string;
  has(path: string): boolean;
  read(path: string): Uint8Array;
}

export interface ImportOptions {
  /** The profile (folder) name; from the URDF's robot name when absent. */
  name?: string;
  /** A mesh larger than this is warned about, bytes. */
  maxMeshBytes: number;
  /** A mesh with more triangles than this is warned about. */
  maxMeshTriangles: number;
}

export const DEFAULT_IMPORT_OPTIONS: ImportOptions = {
  maxMeshBytes: 5 * 1024 * 1024,
  maxMeshTriangles: 200_000,
};

export interface ImportPlan {
  name: string;
  /** Files to write, relative to the robot's folder. */
  files: { path: string; data: Uint8Array | string }[];
  profile: DerivedProfile;
  /** Things a user should know (large meshes, missing collision meshes). */
  warnings: string[];
}

export type ImportResult = { ok: true; plan: ImportPlan } | { ok: false; errors: string[] };

export function planImport(source: ImportSource, opts: Partial<ImportOptions> = {}): ImportResult {
  const o = { ...DEFAULT_IMPORT_OPTIONS, ...opts };
  const doc = parseUrdfXml(source.urdfText);
  const robotName = (doc.ok && attribute(doc.robot, 'name')) || '';
  const name = o.name ?? profileNameFrom(robotName);
  const urdfFile = `${name}.urdf`;
  const errors: string[] = [];
  const warnings: string[] = [];
  const resolved = new Map<string, string>();
  const visual = new Set<string>();
  for (const ref of meshRefs(source.urdfText)) {
    const where = ref.visual ? 'visual' : 'collision';
    const kind = importMeshKind(ref.filename);
    const path = resolveMeshPath(ref.filename, source.urdfPath, (p) => source.has(p));
    const problem = !kind
      ? `mesh ${ref.filename} (${where} of link "${ref.link}"): format not readable (STL, OBJ or DAE)`
      : !path
        ? `mesh ${ref.filename} (${where} of link "${ref.link}") is missing: not found from ${source.urdfPath}`
        : null;
    if (problem) {
      if (ref.visual) errors.push(problem);
      else warnings.push(`${problem}; the HUD does not draw collisions, left as it is`);
      continue;
    }
    resolved.set(ref.filename, path!);
    if (ref.visual) visual.add(path!);
  }
  const derived = deriveProfile(source.urdfText, name, urdfFile);
  if (!derived.ok) errors.unshift(...derived.errors);
  if (errors.length || !derived.ok) return { ok: false, errors };

  const root = commonDir([...new Set(resolved.values())]);
  const target = (p: string) => `meshes/${inside(root, p)}`;
  const files: ImportPlan['files'] = [];
  for (const p of new Set(resolved.values())) {
    const data = source.read(p);
    const kind = importMeshKind(p)!;
    const triangles = meshTriangles(kind, data);
    if (Number.isNaN(triangles)) {
      const why = `mesh ${p}: not a readable ${kind.toUpperCase()} file`;
      if (visual.has(p)) errors.push(why);
      else warnings.push(`${why}; a collision mesh only, copied as it is`);
    }
    if (data.length > o.maxMeshBytes)
      warnings.push(
        `mesh ${target(p)}: ${(data.length / 1048576).toFixed(1)} MB, heavy for a web page (> ${(o.maxMeshBytes / 1048576).toFixed(0)} MB)`,
      );
    if (triangles > o.maxMeshTriangles)
      warnings.push(
        `mesh ${target(p)}: ${triangles} triangles, heavy for a web page (> ${o.maxMeshTriangles})`,
      );
    files.push({ path: target(p), data });
  }
  if (errors.length) return { ok: false, errors };
  const urdf = rewriteMeshPaths(derived.derived.urdf, (f) => {
    const p = resolved.get(f);
    return p === undefined ? null : target(p);
  });
  files.unshift({ path: urdfFile, data: urdf });
  files.push({ path: 'profile.json', data: `${JSON.stringify(derived.derived.json, null, 2)}\n` });
  return { ok: true, plan: { name, files, profile: derived.derived, warnings } };
}
