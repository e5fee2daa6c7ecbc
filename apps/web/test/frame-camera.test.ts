/**
 * The view is framed by the robot's size (robots/sceneHooks.ts `frameCamera`): the 5-axis arm
 * keeps the default view; a 1.1 m arm, whose top the default view cut off, is framed whole,
 * and framing again after a switch gives the default view back. Three's math only; the orbit
 * controls are a plain object with what `frameCamera` reads and writes.
 */
import { describe, expect, test } from 'vitest';
import * as THREE from 'three';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { frameCamera } from '../src/scene/sceneHooks.ts';

/** The Viewer's default camera and orbit target, and a scene. */
function view() {
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 20);
  camera.position.set(0.86, 0.6, 1.0);
  const target = new THREE.Vector3(0, 0.21, 0);
  const controls = {
    target,
    maxDistance: 4,
    update: () => camera.lookAt(target),
  } as unknown as OrbitControls;
  controls.update();
  return { scene, camera, controls };
}

/** A box robot standing on the floor (three's y up), `h` m tall. */
function robot(h: number, w = 0.2): THREE.Object3D {
  const m = new THREE.Mesh(new THREE.BoxGeometry(w, h, w));
  m.position.y = h / 2;
  return m;
}

/** Largest |x| or |y| of the robot's box corners in normalised device coordinates. */
function extent(v: ReturnType<typeof view>, r: THREE.Object3D): number {
  v.camera.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(r);
  let worst = 0;
  for (let i = 0; i < 8; i++) {
    const p = new THREE.Vector3(
      i & 1 ? box.max.x : box.min.x,
      i & 2 ? box.max.y : box.min.y,
      i & 4 ? box.max.z : box.min.z,
    ).project(v.camera);
    worst = Math.max(worst, Math.abs(p.x), Math.abs(p.y));
  }
  return worst;
}

describe('frameCamera', () => {
  test('a 1.1 m arm is framed whole; the 0.5 m arm keeps the default view', () => {
    const v = view();
    const tall = robot(1.1);
    v.scene.add(tall);
    expect(extent(v, tall)).toBeGreaterThan(1); // the default view cuts off its top
    frameCamera(v, tall);
    expect(extent(v, tall)).toBeLessThan(1);
    expect(extent(v, tall)).toBeGreaterThan(0.5); // not a speck either
    tall.removeFromParent();

    const small = robot(0.5, 0.15);
    v.scene.add(small);
    frameCamera(v, small); // a fleet switch back: the default view again
    expect(v.camera.position.distanceTo(new THREE.Vector3(0.86, 0.6, 1.0))).toBeLessThan(1e-9);
    expect(v.controls.target.distanceTo(new THREE.Vector3(0, 0.21, 0))).toBeLessThan(1e-9);
  });
});
