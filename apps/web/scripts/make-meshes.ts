/**
 * Generates the binary STL meshes of the armtwin5 model (public/models/armtwin5/meshes/*.stl)
 * from three.js primitives. Run from the repo root:
 *
 *     npx tsx apps/web/scripts/make-meshes.ts
 *
 * Units are metres, z up, each mesh in its URDF link's frame (the link's joint is the origin).
 * The dimensions that matter to the kinematics live in the URDF; these only have to look right.
 */
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { meshParts, writeStl, type Part } from '../../../scripts/meshes/parts.ts';

const OUT_DIR = path.resolve(
  fileURLToPath(import.meta.url),
  '../../../../public/models/armtwin5/meshes',
);
const { box, cylZ, cylY } = meshParts(40);


/** A rounded beam along z from z0 to z1: a box with half-cylinder ends around y. */
function beam(width: number, depth: number, z0: number, z1: number): Part[] {
  return [
    box(width, depth, z1 - z0, 0, 0, (z0 + z1) / 2),
    cylY(width / 2, depth, 0, 0, z0),
    cylY(width / 2, depth, 0, 0, z1),
  ];
}

const MESHES: Record<string, Part[]> = {
  // Fixed pedestal: a wide foot and a collar, floor (z = 0) to 40 mm.
  base: [cylZ(0.075, 0, 0.012), cylZ(0.068, 0.012, 0.02, 0, 0, 0.06), cylZ(0.05, 0.02, 0.04)],
  // Base yaw (servo 000): turntable, column and the shoulder's two cheek plates around y.
  turret: [
    cylZ(0.056, 0.04, 0.056),
    box(0.07, 0.07, 0.03, 0, 0, 0.071),
    box(0.05, 0.008, 0.06, 0, 0.033, 0.095),
    box(0.05, 0.008, 0.06, 0, -0.033, 0.095),
    cylY(0.022, 0.075, 0, 0, 0.1),
    box(0.03, 0.012, 0.02, -0.03, 0, 0.07), // a servo tab at the back, so the yaw reads
  ],
  // Shoulder (servo 001) → elbow: 105 mm, a wide hub at each end.
  upper_arm: [...beam(0.036, 0.05, 0, 0.105), cylY(0.024, 0.056, 0, 0, 0)],
  // Elbow (servo 002) → wrist: 98 mm, narrower and thinner.
  forearm: [...beam(0.028, 0.036, 0, 0.098), cylY(0.019, 0.062, 0, 0, 0)],
  // Wrist pitch (servo 003): the pitch hub and the roll servo's body.
  wrist: [cylY(0.016, 0.046, 0, 0, 0), box(0.032, 0.03, 0.03, 0, 0, 0.018)],
  // Wrist roll (servo 004): roll flange and the gripper's palm.
  hand: [
    cylZ(0.02, 0.033, 0.045),
    box(0.07, 0.026, 0.045, 0, 0, 0.0675),
    box(0.05, 0.02, 0.008, 0, 0, 0.094),
  ],
  // Gripper servo horn (servo 005): a disc and an arm on the palm's +y face.
  gripper_horn: [cylY(0.009, 0.004, 0, 0, 0), box(0.004, 0.004, 0.022, 0, 0, 0.007)],
  // One finger: pivot at its origin, tip 55 mm up (at the gripper tip when closed).
  finger: [box(0.008, 0.018, 0.055, 0, 0, 0.0275), cylY(0.006, 0.018, 0, 0, 0)],
};

for (const [name, parts] of Object.entries(MESHES)) writeStl(OUT_DIR, name, parts);
