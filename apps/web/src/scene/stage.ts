/**
 * Everything in the scene that is not the arm: background, lights with shadows, the floor with
 * a grid, the z-up "world" group the arm lives in, and the Cartesian target marker.
 * three.js is y-up; the arm's frame (and the URDF) is z-up, so `world` is turned −90° about x:
 * inside it, (x, y, z) are the arm's metres and z = 0 is the floor.
 */
import * as THREE from 'three';
import type { MaterialFactory } from './loadRobot.ts';

export interface Stage {
  /** The arm's z-up frame, metres. */
  world: THREE.Group;
  /** The floor plane in three's (y-up) coordinates, for picking. */
  floorPlane: THREE.Plane;
  marker: THREE.Group;
  markerOk: boolean;
  placeMarker(x: number, y: number, z: number, ok: boolean): void;
}

const OK_COLOUR = new THREE.Color(0x22c55e);
const BAD_COLOUR = new THREE.Color(0xef4444);

export function createStage(scene: THREE.Scene): Stage {
  scene.background = new THREE.Color(0x1b2230);
  scene.fog = new THREE.Fog(0x1b2230, 2.5, 6);

  scene.add(new THREE.HemisphereLight(0xdde8ff, 0x2a2f38, 1.4));
  const sun = new THREE.DirectionalLight(0xffffff, 2.6);
  sun.position.set(0.6, 1.2, 0.4);
  sun.castShadow = true;
  sun.shadow.mapSize.set(2048, 2048);
  const cam = sun.shadow.camera;
  cam.left = cam.bottom = -0.6;
  cam.right = cam.top = 0.6;
  cam.near = 0.1;
  cam.far = 3;
  sun.shadow.bias = -0.0005;
  sun.shadow.normalBias = 0.01;
  scene.add(sun);
  const fill = new THREE.DirectionalLight(0x9fb8ff, 0.6);
  fill.position.set(-0.8, 0.5, -0.6);
  scene.add(fill);

  const floor = new THREE.Mesh(
    new THREE.CircleGeometry(3, 64),
    new THREE.MeshStandardMaterial({ color: 0x3a4352, roughness: 0.95, metalness: 0 }),
  );
  floor.rotation.x = -Math.PI / 2;
  floor.receiveShadow = true;
  floor.name = 'floor';
  scene.add(floor);
  // 1 m grid, 50 mm cells, and a brighter 100 mm-ring workspace hint.
  const grid = new THREE.GridHelper(1, 20, 0x8090a8, 0x56627a);
  grid.position.y = 0.0005;
  (grid.material as THREE.Material).transparent = true;
  (grid.material as THREE.Material).opacity = 0.6;
  scene.add(grid);
  const reach = new THREE.Mesh(
    new THREE.RingGeometry(0.35, 0.353, 96),
    new THREE.MeshBasicMaterial({ color: 0x7dd3fc, transparent: true, opacity: 0.5 }),
  );
  reach.rotation.x = -Math.PI / 2;
  reach.position.y = 0.001;
  scene.add(reach);

  const world = new THREE.Group();
  world.name = 'world (z up)';
  world.rotation.x = -Math.PI / 2;
  scene.add(world);

  // Target marker: a sphere at the target and a thin line down to the floor.
  const markerMaterial = new THREE.MeshBasicMaterial({ color: OK_COLOUR });
  const marker = new THREE.Group();
  const ball = new THREE.Mesh(new THREE.SphereGeometry(0.008, 20, 14), markerMaterial);
  const stemGeometry = new THREE.BufferGeometry().setFromPoints([
    new THREE.Vector3(0, 0, 0),
    new THREE.Vector3(0, 0, -1),
  ]);
  const stem = new THREE.Line(
    stemGeometry,
    new THREE.LineDashedMaterial({ color: 0xffffff, dashSize: 0.01, gapSize: 0.008 }),
  );
  stem.computeLineDistances();
  marker.add(ball, stem);
  marker.visible = false;
  world.add(marker);

  const stage: Stage = {
    world,
    floorPlane: new THREE.Plane(new THREE.Vector3(0, 1, 0), 0),
    marker,
    markerOk: true,
    placeMarker(x, y, z, ok) {
      marker.position.set(x, y, z);
      stem.scale.z = Math.max(z, 0.0001);
      stem.visible = z > 0;
      markerMaterial.color.copy(ok ? OK_COLOUR : BAD_COLOUR);
      stage.markerOk = ok;
    },
  };
  return stage;
}

/** The ghost's look: one translucent cyan for every part. */
export const ghostMaterial: MaterialFactory = () =>
  new THREE.MeshStandardMaterial({
    color: 0x67e8f9,
    emissive: 0x0e7490,
    emissiveIntensity: 0.4,
    transparent: true,
    opacity: 0.35,
    depthWrite: false,
    // Strictly nearer only: where the ghost coincides with the live arm it is not drawn (no stripes).
    depthFunc: THREE.LessDepth,
    roughness: 0.4,
  });
