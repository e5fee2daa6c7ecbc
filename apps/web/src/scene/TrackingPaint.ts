/**
 * Paints the live arm's links by their joint's tracking error (store/trackingError.ts): each
 * servo's URDF joint's child link (up to the next joint) gets its own material, a copy of the
 * link's own with the ramp's colour; switched off, every mesh gets its own material back.
 * `update` runs every frame and touches materials only when a colour or the switch changed.
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { TrackingErrors, TrackingLevel } from '../core/store/trackingError.ts';

export class TrackingPaint {
  /** Servo i's link meshes and their own materials. */
  private readonly links: { mesh: THREE.Mesh; own: THREE.Material | THREE.Material[] }[][];
  /** Servo i's paint (one material for its whole link), made on first use. */
  private readonly paints: (THREE.MeshStandardMaterial | null)[];
  private applied: number[];
  private seen = -1;
  private on = false;
  /** The level each servo's link is painted at now ('none' = not painted): tests, debug hook. */
  readonly levels: TrackingLevel[];

  constructor(robot: URDFRobot, jointNames: readonly string[]) {
    this.links = jointNames.map((name) => {
      const out: { mesh: THREE.Mesh; own: THREE.Material | THREE.Material[] }[] = [];
      const link = robot.joints[name]?.children.find(
        (c) => (c as { isURDFLink?: boolean }).isURDFLink,
      );
      const visit = (o: THREE.Object3D) => {
        if ((o as { isURDFJoint?: boolean }).isURDFJoint) return; // the next joint's link
        const mesh = o as THREE.Mesh;
        if (mesh.isMesh) out.push({ mesh, own: mesh.material });
        o.children.forEach(visit);
      };
      link?.children.forEach(visit);
      return out;
    });
    this.paints = jointNames.map(() => null);
    this.applied = jointNames.map(() => -1);
    this.levels = jointNames.map(() => 'none');
  }

  /** Paints (or unpaints) from `t`; true when anything drawn changed. */
  update(t: Pick<TrackingErrors, 'active' | 'version' | 'colours' | 'levels'>): boolean {
    const on = t.active;
    if (on === this.on && (!on || t.version === this.seen)) return false;
    this.on = on;
    this.seen = t.version;
    let changed = false;
    for (let i = 0; i < this.links.length; i++) {
      const colour = on ? (t.colours[i] ?? -1) : -1;
      this.levels[i] = colour < 0 ? 'none' : (t.levels[i] ?? 'none');
      if (colour === this.applied[i]) continue;
      this.applied[i] = colour;
      changed = true;
      if (colour < 0) {
        for (const { mesh, own } of this.links[i]!) mesh.material = own;
        continue;
      }
      let paint = this.paints[i];
      if (!paint) {
        paint = this.paints[i] = new THREE.MeshStandardMaterial({
          roughness: 0.55,
          metalness: 0.1,
        });
      }
      paint.color.setHex(colour);
      for (const { mesh } of this.links[i]!) mesh.material = paint;
    }
    return changed;
  }

  /** Own materials back, paints disposed (the robot is being replaced). */
  dispose(): void {
    for (const link of this.links) for (const { mesh, own } of link) mesh.material = own;
    for (const p of this.paints) p?.dispose();
  }
}
