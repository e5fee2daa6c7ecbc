/**
 * The twin's named points a user can match to a camera's picture (four-point calibration): the
 * origin of each link of the live model as drawn now, in mm in the arm's frame (§4). Links at
 * the same place as an earlier one (a turret on its base, a hand on its wrist) are left out.
 */
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { Vec3 } from '@armtwin/camera/client';

export interface TwinPoint {
  name: string;
  mm: Vec3;
}

/** Points closer than this to an earlier one are the same point to a clicking user, mm. */
const SAME_POINT_MM = 2;
const scratch = new THREE.Vector3();

export function twinPoints(robot: URDFRobot | null, world: THREE.Object3D): TwinPoint[] {
  if (!robot) return [];
  robot.updateMatrixWorld(true);
  world.updateMatrixWorld();
  const out: TwinPoint[] = [];
  for (const [name, link] of Object.entries(robot.links)) {
    link.getWorldPosition(scratch);
    world.worldToLocal(scratch);
    const mm: Vec3 = [scratch.x * 1000, scratch.y * 1000, scratch.z * 1000];
    if (
      out.some((p) => Math.hypot(p.mm[0] - mm[0], p.mm[1] - mm[1], p.mm[2] - mm[2]) < SAME_POINT_MM)
    )
      continue;
    out.push({ name, mm });
  }
  return out;
}

/** The tool tip's name among `points`: a link called `tip`, else the last one. */
export const tipName = (points: readonly TwinPoint[]): string =>
  points.find((p) => p.name === 'tip')?.name ?? points.at(-1)?.name ?? '';
