/**
 * The 3D view's camera and orbit controls as they start, the same on the page side
 * (./render/SceneClient.ts) and in the scene runtime's stand-in controls: where the camera stands,
 * what it orbits, how far it may go (frameCamera, ../robots/sceneHooks.ts, scales these to a
 * robot larger than the default view shows).
 */
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export const VIEW_HOME = {
  position: [0.86, 0.6, 1.0],
  target: [0, 0.21, 0],
  maxDistance: 4,
} as const;

/** The view's perspective camera at its home position. */
export function createViewCamera(): THREE.PerspectiveCamera {
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 20);
  camera.position.set(...VIEW_HOME.position);
  return camera;
}

/** Orbit controls on `element` around the home target; `onChange` when the user moved the view. */
export function createOrbitControls(
  camera: THREE.PerspectiveCamera,
  element: HTMLElement,
  onChange: () => void,
): OrbitControls {
  const controls = new OrbitControls(camera, element);
  controls.target.set(...VIEW_HOME.target);
  controls.enableDamping = false;
  controls.maxDistance = VIEW_HOME.maxDistance;
  controls.addEventListener('change', onChange);
  return controls;
}
