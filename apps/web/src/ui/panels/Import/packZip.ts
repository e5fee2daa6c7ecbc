/**
 * Packs files into a .zip with fflate (stored: meshes and URDFs travel over loopback or a LAN,
 * and the server's limit counts the upload), so a robot folder dropped on the page travels to
 * `armtwin up` as one archive, the same kind a zipped folder is. Names are '/'-separated paths.
 */
import { zipSync, type Zippable } from 'fflate';

export interface ZipEntry {
  path: string;
  data: Uint8Array;
}

export function packZip(entries: readonly ZipEntry[]): Uint8Array {
  const files: Zippable = {};
  for (const e of entries) files[e.path] = [e.data, { level: 0 }];
  return zipSync(files);
}
