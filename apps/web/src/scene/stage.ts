/**
 * Everything in the scene that is not the arm: background, lights with shadows, the floor with
 * a grid, the z-up "world" group the arm lives in, and the Cartesian target marker.
 * three.js is y-up; the arm's frame (and the URDF) is z-up, so `world` is turned −90° about x:
 * inside it, (x, y, z) are the arm's metres and z = 0 is the floor.
 */
import * as THREE from 'three';

export interface Stage {
  /** The arm's z-up frame, metres. */
  world: THREE.Group;
  /** The floor plane in three's (y-up) coordinates, for picking. */
  floorPlane: THREE.Plane;
  marker: THREE.Group;
  markerOk: boolean;
  placeMarker(x: number, y: number, z: number, ok: boolean): void;
}

/** Half the side of the square the sun's shadow camera covers, m (the small arm's). */
const SHADOW_EXTENT_M = 0.6;
const FLOOR_ALBEDO = new THREE.Color(0x3a4352);

/** Cosine between a light's direction (from its position toward the origin) and the floor's up. */
function upCos(position: THREE.Vector3): number {
  return Math.max(0, position.y / position.length());
}

/**
 * A matte floor's colour lit by `lights` (irradiance toward the up normal: the hemisphere
 * light's sky colour, each directional light's intensity × cosine), as three.js's Lambert BRDF
 * (albedo / π) gives it, and the opacity of black that darkens it to its shade when the light
 * of `blocked` intensity is shadowed (blending happens on sRGB values). Pure.
 */
export function floorLook(
  albedo: THREE.Color,
  lights: { colour: THREE.Color; intensity: number }[],
): { lit: THREE.Color; shadowOpacity(blocked: number): number } {
  const e = new THREE.Color(0, 0, 0);
  for (const l of lights) e.add(l.colour.clone().multiplyScalar(l.intensity));
  const lit = albedo
    .clone()
    .multiply(e)
    .multiplyScalar(1 / Math.PI);
  return {
    lit,
    shadowOpacity(blocked) {
      const shade = albedo
        .clone()
        .multiply(e.clone().sub(new THREE.Color(blocked, blocked, blocked)))
        .multiplyScalar(1 / Math.PI);
      const a = srgbLuma(lit);
      return a > 0 ? Math.min(1, Math.max(0, 1 - srgbLuma(shade) / a)) : 0;
    },
  };
}

/** Mean of the sRGB-encoded channels of a linear colour. */
function srgbLuma(c: THREE.Color): number {
  const s = c.clone().convertLinearToSRGB();
  return (Math.min(1, s.r) + Math.min(1, s.g) + Math.min(1, s.b)) / 3;
}

const OK_COLOUR = new THREE.Color(0x22c55e);
const BAD_COLOUR = new THREE.Color(0xef4444);

export function createStage(scene: THREE.Scene): Stage {
  scene.background = new THREE.Color(0x1b2230);
  scene.fog = new THREE.Fog(0x1b2230, 2.5, 6);

  const hemi = new THREE.HemisphereLight(0xdde8ff, 0x2a2f38, 1.4);
  scene.add(hemi);
  const sun = new THREE.DirectionalLight(0xffffff, 2.6);
  sun.position.set(0.6, 1.2, 0.4);
  sun.castShadow = true;
  // 1024² over the 1.2 m frustum: ~1.2 mm a texel, a quarter of 2048²'s fill on every shadow pass.
  sun.shadow.mapSize.set(1024, 1024);
  const cam = sun.shadow.camera;
  cam.left = cam.bottom = -SHADOW_EXTENT_M;
  cam.right = cam.top = SHADOW_EXTENT_M;
  cam.near = 0.1;
  cam.far = 3;
  sun.shadow.bias = -0.0005;
  sun.shadow.normalBias = 0.01;
  scene.add(sun);
  const fill = new THREE.DirectionalLight(0x9fb8ff, 0.6);
  fill.position.set(-0.8, 0.5, -0.6);
  scene.add(fill);

  // The floor is flat and matte, so lit it is one colour: drawn unlit in that colour (the
  // lighting of a Lambert floor under these lights, worked out once), with the shadows on a
  // disc of ShadowMaterial over the shadow camera's square. Lighting and shadowing every floor
  // pixel was most of a frame with software WebGL; now only the disc samples the shadow map.
  const look = floorLook(FLOOR_ALBEDO, [
    { colour: hemi.color, intensity: hemi.intensity },
    { colour: sun.color, intensity: sun.intensity * upCos(sun.position) },
    { colour: fill.color, intensity: fill.intensity * upCos(fill.position) },
  ]);
  const floor = new THREE.Mesh(
    new THREE.CircleGeometry(3, 64),
    new THREE.MeshBasicMaterial({ color: look.lit }),
  );
  floor.rotation.x = -Math.PI / 2;
  floor.name = 'floor';
  scene.add(floor);
  const shadowCatcher = new THREE.Mesh(
    new THREE.CircleGeometry(SHADOW_EXTENT_M * Math.SQRT2, 64),
    new THREE.ShadowMaterial({ opacity: look.shadowOpacity(sun.intensity * upCos(sun.position)) }),
  );
  shadowCatcher.rotation.x = -Math.PI / 2;
  shadowCatcher.position.y = 0.0002;
  shadowCatcher.receiveShadow = true;
  shadowCatcher.name = 'floor-shadow';
  scene.add(shadowCatcher);
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
