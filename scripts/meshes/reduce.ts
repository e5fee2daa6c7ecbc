/**
 * Reduces a robot's STL meshes for a web page without visible loss: each mesh is welded
 * (three.js mergeVertices) and simplified by meshoptimizer's simplifier under an absolute
 * error bound (default 0.1 mm: far below a pixel at any distance the HUD draws an arm from),
 * then written back as binary STL. Used for the meshes that come with a robot's real
 * description (public/models/so101, so100: CAD exports of about a megabyte a part); the
 * generated models (armtwin5, track6) are low-poly from the start (parts.ts).
 *
 *   npx tsx scripts/meshes/reduce.ts public/models/so101/meshes [--error 0.0001]
 */
import fs from 'node:fs';
import path from 'node:path';
import * as THREE from 'three';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { mergeVertices } from 'three/examples/jsm/utils/BufferGeometryUtils.js';
import { MeshoptSimplifier } from 'meshoptimizer';
import { writeStl } from './parts.ts';

/** Simplifies `geometry` (metres) so no surface moves more than `maxError` metres. */
export async function reduceGeometry(
  geometry: THREE.BufferGeometry,
  maxError: number,
): Promise<{ geometry: THREE.BufferGeometry; error: number }> {
  await MeshoptSimplifier.ready;
  const plain = new THREE.BufferGeometry();
  plain.setAttribute('position', geometry.getAttribute('position'));
  const welded = mergeVertices(plain, 1e-7);
  const positions = welded.getAttribute('position').array as Float32Array;
  const index = new Uint32Array(welded.getIndex()!.array);
  const [kept, error] = MeshoptSimplifier.simplify(index, positions, 3, 0, maxError, [
    'ErrorAbsolute',
    'LockBorder',
  ]);
  const out = new THREE.BufferGeometry();
  out.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  out.setIndex(new THREE.BufferAttribute(kept, 1));
  return { geometry: out.toNonIndexed(), error };
}

async function main(argv: string[]): Promise<void> {
  const dir = argv[0];
  const at = argv.indexOf('--error');
  const maxError = at >= 0 ? Number(argv[at + 1]) : 1e-4;
  if (!dir || !(maxError > 0)) {
    console.error('usage: reduce.ts <meshes folder> [--error METRES]');
    process.exit(2);
  }
  const loader = new STLLoader();
  for (const name of fs.readdirSync(dir).filter((f) => /\.stl$/i.test(f))) {
    const file = path.join(dir, name);
    const bytes = fs.readFileSync(file);
    const input = loader.parse(
      bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length),
    );
    const before = input.getAttribute('position').count / 3;
    const { geometry, error } = await reduceGeometry(input, maxError);
    const after = geometry.getAttribute('position').count / 3;
    const base = name.slice(0, -'.stl'.length);
    writeStl(dir, base, [geometry]);
    if (name !== `${base}.stl`) fs.renameSync(path.join(dir, `${base}.stl`), file);
    console.log(`  ${name}: ${before} → ${after} triangles, error ${(error * 1000).toFixed(3)} mm`);
  }
}

if (import.meta.url === `file://${process.argv[1]}`) await main(process.argv.slice(2));
