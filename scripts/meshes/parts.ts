/**
 * The building blocks of the generated robot meshes (apps/web/scripts/make-meshes.ts for
 * armtwin5, public/models/track6/make-meshes.ts for track6): three.js primitives placed in a
 * link's frame (metres, z up), and a binary STL writer.
 */
import fs from 'node:fs';
import path from 'node:path';
import * as THREE from 'three';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';

export type Part = THREE.BufferGeometry;

/** Primitives with `segments` facets round each cylinder. */
export function meshParts(segments: number) {
  return {
    /** A box of size (sx, sy, sz) centred at (x, y, z). */
    box: (sx: number, sy: number, sz: number, x = 0, y = 0, z = 0): Part =>
      new THREE.BoxGeometry(sx, sy, sz).translate(x, y, z),
    /** A cylinder along z, radius r (rTop at z1), from z0 to z1, centred on (x, y). */
    cylZ: (r: number, z0: number, z1: number, x = 0, y = 0, rTop = r): Part =>
      new THREE.CylinderGeometry(rTop, r, z1 - z0, segments)
        .rotateX(Math.PI / 2)
        .translate(x, y, (z0 + z1) / 2),
    /** A cylinder along y (a pitch axis's hub), radius r, width w, centred at (x, y, z). */
    cylY: (r: number, w: number, x = 0, y = 0, z = 0): Part =>
      new THREE.CylinderGeometry(r, r, w, segments).translate(x, y, z),
    /** A cylinder along x, radius r (rEnd at x1), from x0 to x1, centred on (y, z). */
    cylX: (r: number, x0: number, x1: number, y = 0, z = 0, rEnd = r): Part =>
      new THREE.CylinderGeometry(rEnd, r, x1 - x0, segments)
        .rotateZ(-Math.PI / 2)
        .translate((x0 + x1) / 2, y, z),
  };
}

/** Writes `parts` as one binary STL file `<outDir>/<name>.stl`. */
export function writeStl(outDir: string, name: string, parts: Part[]): void {
  const group = new THREE.Group();
  for (const geometry of parts) group.add(new THREE.Mesh(geometry));
  group.updateMatrixWorld(true);
  const data = new STLExporter().parse(group, { binary: true }) as DataView;
  fs.mkdirSync(outDir, { recursive: true });
  const file = path.join(outDir, `${name}.stl`);
  fs.writeFileSync(file, new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  console.log(`${path.relative(process.cwd(), file)}: ${data.byteLength} bytes`);
}
