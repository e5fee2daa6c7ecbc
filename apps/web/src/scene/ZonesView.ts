/**
 * The active robot's keep-out zones (its profile's `keepOut`, docs/protocol.md "Keep-out
 * zones") drawn as translucent amber shapes in the arm's z-up frame: boxes, vertical cylinders,
 * and a plane as a 2 m square on it, tinted on the kept-out side. Rebuilt when the profile
 * changes (`show`), never per frame.
 */
import * as THREE from 'three';
import type { ProfileKeepOut, Zone } from '@armtwin/robot';

/** Side of the square a plane zone is drawn as, m (planes are infinite). */
const PLANE_DRAWN_M = 2;
const MM = 0.001;

const zoneMaterial = new THREE.MeshStandardMaterial({
  color: 0xf59e0b,
  emissive: 0x78350f,
  emissiveIntensity: 0.3,
  transparent: true,
  opacity: 0.22,
  depthWrite: false,
  side: THREE.DoubleSide,
});
const edgeMaterial = new THREE.LineBasicMaterial({
  color: 0xf59e0b,
  transparent: true,
  opacity: 0.7,
});

function shapeOf(zone: Zone): THREE.Object3D {
  switch (zone.shape) {
    case 'box': {
      const [x0, y0, z0] = zone.min;
      const [x1, y1, z1] = zone.max;
      const g = new THREE.BoxGeometry((x1 - x0) * MM, (y1 - y0) * MM, (z1 - z0) * MM);
      const mesh = new THREE.Mesh(g, zoneMaterial);
      mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(g), edgeMaterial));
      mesh.position.set(((x0 + x1) / 2) * MM, ((y0 + y1) / 2) * MM, ((z0 + z1) / 2) * MM);
      return mesh;
    }
    case 'cylinder': {
      const h = zone.zMax - zone.zMin;
      const g = new THREE.CylinderGeometry(zone.radius * MM, zone.radius * MM, h * MM, 32);
      g.rotateX(Math.PI / 2); // three's cylinders stand on y; the arm's frame is z-up
      const mesh = new THREE.Mesh(g, zoneMaterial);
      mesh.position.set(zone.center[0] * MM, zone.center[1] * MM, (zone.zMin + h / 2) * MM);
      return mesh;
    }
    case 'plane': {
      const g = new THREE.PlaneGeometry(PLANE_DRAWN_M, PLANE_DRAWN_M);
      const mesh = new THREE.Mesh(g, zoneMaterial);
      mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(g), edgeMaterial));
      const [nx, ny, nz] = zone.normal;
      mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(nx, ny, nz));
      mesh.position.set(zone.point[0] * MM, zone.point[1] * MM, zone.point[2] * MM);
      return mesh;
    }
    default: {
      const never: never = zone;
      return never;
    }
  }
}

export class ZonesView {
  readonly group = new THREE.Group();
  private shown = '';

  constructor(world: THREE.Object3D) {
    this.group.name = 'keep-out zones';
    this.group.renderOrder = 2;
    world.add(this.group);
  }

  /** The zones drawn now, by name (for tests and the console). */
  get names(): string[] {
    return this.group.children.map((o) => o.name);
  }

  /** Draws these zones instead of the ones before; true when anything changed. */
  show(keepOut: ProfileKeepOut | undefined): boolean {
    const key = JSON.stringify(keepOut?.zones ?? []);
    if (key === this.shown) return false;
    this.shown = key;
    for (const o of [...this.group.children]) {
      o.removeFromParent();
      o.traverse((c) => (c as THREE.Mesh).geometry?.dispose());
    }
    for (const zone of keepOut?.zones ?? []) {
      const o = shapeOf(zone);
      o.name = zone.name;
      this.group.add(o);
    }
    return true;
  }
}
