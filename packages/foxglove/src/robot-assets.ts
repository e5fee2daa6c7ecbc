/**
 * The robot description as Foxglove reads it from a channel, and the files it names: a URDF's
 * relative mesh paths (`meshes/base.stl`, as `armtwin robot import` writes them) become
 * `package://<profile>/meshes/base.stl`, and the protocol's asset fetching resolves
 * `package://<profile>/<path>` in the robot folders, never outside them. Node (reads files).
 */
import fs from 'node:fs/promises';
import path from 'node:path';

/** `filename="…"` of a URDF whose value has no scheme, rewritten under `package://<name>/`. */
export function urdfWithPackagePaths(urdf: string, name: string): string {
  return urdf.replace(/filename="([^"]*)"/g, (whole, file: string) =>
    /^[a-z][a-z0-9+.-]*:\/\//i.test(file) || file.startsWith('/')
      ? whole
      : `filename="package://${name}/${file.replace(/^\.\//, '')}"`,
  );
}

export type AssetResult = { ok: true; data: Uint8Array } | { ok: false; error: string };

/** The bytes of `package://<name>/<path>` from the first of `modelDirs` that holds it. */
export async function fetchRobotAsset(
  uri: string,
  modelDirs: readonly string[],
): Promise<AssetResult> {
  const m = /^package:\/\/([a-z0-9_-]{1,32})\/(.+)$/.exec(uri);
  if (!m) return { ok: false, error: `not an armtwin robot asset: ${uri.slice(0, 200)}` };
  for (const dir of modelDirs) {
    const root = path.resolve(dir, m[1]!);
    const file = path.resolve(root, decodeURIComponent(m[2]!));
    if (!file.startsWith(root + path.sep))
      return { ok: false, error: `outside the robot's folder: ${uri.slice(0, 200)}` };
    try {
      return { ok: true, data: await fs.readFile(file) };
    } catch {
      // the next folder may hold it
    }
  }
  return { ok: false, error: `no such robot file: ${uri.slice(0, 200)}` };
}
