/**
 * Where a robot import reads from, as an `ImportSource`: a .urdf file (its meshes looked up on
 * disk from its folder up), a folder holding one .urdf, or a .zip holding one, on disk
 * (`armtwin robot import`) or as bytes (`zipSource`: a folder or zip dropped on the HUD and
 * sent to `armtwin up`). Node only.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { ImportSource } from '../import/plan-import.ts';
import { readZip } from './zip.ts';

/** How deep a folder is searched for its URDF. */
const SEARCH_DEPTH = 6;

function pickUrdf(candidates: string[], where: string): string {
  const urdfs = candidates.filter((f) => /\.urdf$/i.test(f)).sort();
  if (urdfs.length === 1) return urdfs[0]!;
  if (urdfs.length === 0) {
    const xacro = candidates.some((f) => /\.xacro$/i.test(f));
    throw new Error(
      `no .urdf file in ${where}${xacro ? ' (only .xacro: expand it first, e.g. `xacro robot.urdf.xacro > robot.urdf`)' : ''}`,
    );
  }
  throw new Error(
    `${urdfs.length} .urdf files in ${where}: give the one to import (${urdfs.join(', ')})`,
  );
}

function listFiles(dir: string, depth = 0): string[] {
  if (depth > SEARCH_DEPTH) return [];
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(dir, e.name);
    return e.isDirectory() ? listFiles(p, depth + 1) : e.isFile() ? [p] : [];
  });
}

const onDisk = (urdfPath: string): ImportSource => ({
  urdfPath: urdfPath.split(path.sep).join('/'),
  urdfText: fs.readFileSync(urdfPath, 'utf8'),
  has: (p) => {
    try {
      return fs.statSync(p).isFile();
    } catch {
      return false;
    }
  },
  read: (p) => fs.readFileSync(p),
});

export function importSource(input: string): ImportSource {
  const abs = path.resolve(input);
  const stat = fs.statSync(abs, { throwIfNoEntry: false });
  if (!stat) throw new Error(`${input}: no such file or folder`);
  if (stat.isDirectory()) return onDisk(pickUrdf(listFiles(abs), input));
  if (/\.zip$/i.test(abs)) return zipSource(fs.readFileSync(abs), input);
  if (/\.urdf$/i.test(abs)) return onDisk(abs);
  if (/\.xacro$/i.test(abs))
    throw new Error(
      `${input} is xacro: expand it to a plain .urdf first (e.g. \`xacro ${path.basename(input)} > robot.urdf\`)`,
    );
  throw new Error(`${input}: give a .urdf file, a folder holding one, or a .zip holding one`);
}

/**
 * A .zip's bytes holding one .urdf, or several and `urdf` (a file name or path ending) naming
 * the one to import; `where` names the zip in errors. Throws when it cannot be used.
 */
export function zipSource(bytes: Buffer, where: string, urdf?: string): ImportSource {
  const files = readZip(bytes);
  const names = [...files.keys()];
  const chosen = urdf ? names.filter((n) => n === urdf || n.endsWith(`/${urdf}`)) : names;
  if (urdf && chosen.length === 0) throw new Error(`no ${urdf} in ${where}`);
  const urdfPath = pickUrdf(chosen, where);
  return {
    urdfPath,
    urdfText: new TextDecoder().decode(files.get(urdfPath)),
    has: (p) => files.has(p.replace(/^\//, '')),
    read: (p) => files.get(p.replace(/^\//, ''))!,
  };
}
