/**
 * The HUD's mesh formats: STL in ASCII and binary, OBJ; the format by extension. (DAE needs the
 * browser's DOMParser: the end-to-end robots test loads real DAE meshes in Chromium.)
 */
import * as THREE from 'three';
import { describe, expect, test } from 'vitest';
import { meshKind, parseMesh } from '../src/scene/meshLoaders.ts';

const ASCII_STL = `solid t
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 1 0
 endloop
endfacet
endsolid t
`;

function binaryStl(triangles: number): ArrayBuffer {
  const buf = new ArrayBuffer(84 + 50 * triangles);
  const v = new DataView(buf);
  v.setUint32(80, triangles, true);
  for (let t = 0; t < triangles; t++) {
    const o = 84 + 50 * t;
    v.setFloat32(o + 8, 1, true); // normal z
    v.setFloat32(o + 12 + 12, 1, true); // second vertex x = 1
    v.setFloat32(o + 12 + 24 + 4, 1, true); // third vertex y = 1
  }
  return buf;
}

const bytes = (s: string) => new TextEncoder().encode(s).buffer as ArrayBuffer;

function triangles(obj: THREE.Object3D): number {
  let n = 0;
  obj.traverse((c) => {
    if (c instanceof THREE.Mesh)
      n += (c.geometry as THREE.BufferGeometry).getAttribute('position').count / 3;
  });
  return n;
}

describe('mesh loaders', () => {
  test('the format by extension, case and query ignored', () => {
    expect(meshKind('/models/a/meshes/link0.STL')).toBe('stl');
    expect(meshKind('/m/x.dae?v=2')).toBe('dae');
    expect(meshKind('x.obj')).toBe('obj');
    expect(meshKind('x.ply')).toBeNull();
    expect(meshKind('meshes/noext')).toBeNull();
  });

  test('ASCII and binary STL', () => {
    expect(triangles(parseMesh('stl', bytes(ASCII_STL), 'a.stl'))).toBe(1);
    expect(triangles(parseMesh('stl', binaryStl(3), 'b.stl'))).toBe(3);
  });

  test('normals are computed where the file gives only zeros (facet normal 0 0 0)', () => {
    const zero = ASCII_STL.replace('facet normal 0 0 1', 'facet normal 0 0 0');
    const mesh = parseMesh('stl', bytes(zero), 'z.stl') as THREE.Mesh;
    const n = (mesh.geometry as THREE.BufferGeometry).getAttribute('normal');
    expect(Math.abs(n.getZ(0))).toBeCloseTo(1);
  });

  test('OBJ', () => {
    const obj = 'o t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n';
    expect(triangles(parseMesh('obj', bytes(obj), 'c.obj'))).toBe(2);
  });

  test('an HTML page is not taken for a mesh', () => {
    expect(() => parseMesh('stl', bytes('<!doctype html><html></html>'), 'd.stl')).toThrow();
  });
});
