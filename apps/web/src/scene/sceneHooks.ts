/**
 * What the 3D view needs to show any robot: the ghost's alternative source (the plan preview)
 * and framing the camera, fog, shadows and floor on a robot bigger than the 5-axis arm (track6
 * is 3.7 m long and 2 m tall, a Panda or an iiwa over 1 m; the scene's defaults fit a 0.5 m arm):
 * by the robot's bounding box, on every load (and so on every fleet switch). A robot whose box
 * the default view shows whole gets exactly the default view back.
 */
import * as THREE from 'three';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export type { GhostSource } from '../core/store/viewSources.ts';

interface Framed {
  scene: THREE.Scene;
  camera: THREE.PerspectiveCamera;
  controls: OrbitControls;
}

/**
 * A robot keeps the default view when every corner of its bounding box is seen from the default
 * camera within this fraction of the view's half-width and half-height (a margin round it).
 */
const DEFAULT_VIEW_FILL = 0.9;
/** A robot that does not fit is seen from this many bounding-sphere radii (the whole robot, 40° fov). */
const FIT_DISTANCE = 3.3;

interface Defaults {
  position: THREE.Vector3;
  target: THREE.Vector3;
  maxDistance: number;
  far: number;
  fog: { near: number; far: number } | null;
  sun: { position: THREE.Vector3; extent: number; far: number } | null;
  scale: Map<THREE.Object3D, number>;
}
const defaults = new WeakMap<Framed, Defaults>();

function sunOf(scene: THREE.Scene): THREE.DirectionalLight | null {
  let sun: THREE.DirectionalLight | null = null;
  scene.traverse((o) => {
    if (!sun && (o as THREE.DirectionalLight).isDirectionalLight && o.castShadow)
      sun = o as THREE.DirectionalLight;
  });
  return sun;
}

/** The floor, its shadow disc and the grid (scaled with the robot). */
function groundOf(scene: THREE.Scene): THREE.Object3D[] {
  return scene.children.filter(
    (o) => o.name === 'floor' || o.name === 'floor-shadow' || o.type === 'GridHelper',
  );
}

function remember(v: Framed): Defaults {
  let d = defaults.get(v);
  if (d) return d;
  const sun = sunOf(v.scene);
  const fog = v.scene.fog as THREE.Fog | null;
  d = {
    position: v.camera.position.clone(),
    target: v.controls.target.clone(),
    maxDistance: v.controls.maxDistance,
    far: v.camera.far,
    fog: fog ? { near: fog.near, far: fog.far } : null,
    sun: sun
      ? {
          position: sun.position.clone(),
          extent: sun.shadow.camera.right,
          far: sun.shadow.camera.far,
        }
      : null,
    scale: new Map(groundOf(v.scene).map((o) => [o, o.scale.x])),
  };
  defaults.set(v, d);
  return d;
}

/** Whether the default camera (square view, the narrowest a load sees) shows all of `box`. */
function fitsDefaultView(v: Framed, d: Defaults, box: THREE.Box3): boolean {
  const cam = v.camera.clone();
  cam.aspect = Math.min(1, v.camera.aspect);
  cam.position.copy(d.position);
  cam.lookAt(d.target);
  cam.updateMatrixWorld(true);
  cam.updateProjectionMatrix();
  const p = new THREE.Vector3();
  for (let i = 0; i < 8; i++) {
    p.set(
      i & 1 ? box.max.x : box.min.x,
      i & 2 ? box.max.y : box.min.y,
      i & 4 ? box.max.z : box.min.z,
    );
    p.project(cam);
    if (!(Math.abs(p.x) <= DEFAULT_VIEW_FILL && Math.abs(p.y) <= DEFAULT_VIEW_FILL && p.z < 1))
      return false;
  }
  return true;
}

/** Frames `robot` (already in the scene): the default view when it shows the whole robot, else one that fits. */
export function frameCamera(v: Framed, robot: THREE.Object3D): void {
  const d = remember(v);
  robot.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(robot);
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const small = box.isEmpty() || fitsDefaultView(v, d, box);
  // How much bigger than the default view: the camera `FIT_DISTANCE` radii away.
  const defaultDistance = d.position.distanceTo(d.target);
  const k = small ? 1 : Math.max(1, (FIT_DISTANCE * sphere.radius) / defaultDistance);
  const target = small ? d.target : sphere.center;
  const dir = d.position.clone().sub(d.target).normalize();
  v.controls.target.copy(target);
  v.camera.position.copy(target).addScaledVector(dir, defaultDistance * k);
  v.controls.maxDistance = d.maxDistance * k;
  v.camera.far = d.far * k;
  v.camera.updateProjectionMatrix();
  const fog = v.scene.fog as THREE.Fog | null;
  if (fog && d.fog) {
    fog.near = d.fog.near * k;
    fog.far = d.fog.far * k;
  }
  const sun = sunOf(v.scene);
  if (sun && d.sun) {
    if (small) {
      sun.position.copy(d.sun.position);
      sun.target.position.set(0, 0, 0);
    } else {
      sun.position.copy(target).addScaledVector(d.sun.position, k);
      sun.target.position.copy(target);
    }
    sun.target.updateMatrixWorld();
    const cam = sun.shadow.camera;
    cam.left = cam.bottom = -d.sun.extent * k;
    cam.right = cam.top = d.sun.extent * k;
    cam.far = d.sun.far * k;
    cam.updateProjectionMatrix();
  }
  for (const [o, s] of d.scale) {
    o.scale.setScalar(s * Math.max(1, Math.ceil(k)));
    o.position.x = small ? 0 : target.x;
    o.position.z = small ? 0 : target.z;
  }
  v.controls.update();
}
