/**
 * Generates the binary STL meshes of the track6 model (public/models/track6/meshes/*.stl) from
 * low-poly three.js primitives. Run from the repo root:
 *
 *     npx tsx public/models/track6/make-meshes.ts
 *
 * Metres, z up, each mesh in its URDF link's frame (the link's joint is the origin). The
 * kinematics live in track6.urdf; these only have to look like a generic industrial arm on a
 * floor track (no vendor's shapes). Each file stays well under 200 KB.
 */
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { meshParts, writeStl, type Part } from '../../../scripts/meshes/parts.ts';

const OUT_DIR = path.join(path.dirname(fileURLToPath(import.meta.url)), 'meshes');
const { box, cylZ, cylY, cylX } = meshParts(24);


/** The rail: two beams along x under the carriage's 0…3 m travel, on sleepers. */
function rail(): Part[] {
  const parts = [box(3.9, 0.12, 0.2, 1.5, 0.3, 0.13), box(3.9, 0.12, 0.2, 1.5, -0.3, 0.13)];
  for (let x = -0.4; x <= 3.41; x += 0.6) parts.push(box(0.16, 0.9, 0.03, x, 0, 0.015));
  parts.push(box(0.1, 0.8, 0.3, -0.45, 0, 0.15), box(0.1, 0.8, 0.3, 3.45, 0, 0.15)); // end stops
  return parts;
}

const MESHES: Record<string, Part[]> = {
  rail: rail(),
  // Carriage plate riding the rails, and the robot's pedestal (top at a1, z = 0.35).
  carriage: [box(0.9, 0.9, 0.08, 0, 0, 0.04), cylZ(0.3, 0.08, 0.3), cylZ(0.34, 0.3, 0.35)],
  // A1: turntable, the shoulder housing rising to a2 at (0.35, 0, 0.4), and a2's hub.
  column: [
    cylZ(0.33, 0, 0.12),
    box(0.5, 0.42, 0.22, 0.12, 0, 0.2),
    box(0.26, 0.1, 0.42, 0.35, 0.2, 0.35),
    box(0.26, 0.1, 0.42, 0.35, -0.2, 0.35),
    cylY(0.16, 0.5, 0.35, 0, 0.4),
    box(0.2, 0.3, 0.25, -0.2, 0, 0.25), // motor pack at the back
  ],
  // A2 → A3: 1.15 m upper arm, hubs at both ends.
  upper_arm: [
    box(0.22, 0.2, 1.05, 0, 0, 0.575),
    cylY(0.17, 0.3, 0, 0, 0),
    cylY(0.15, 0.28, 0, 0, 1.15),
  ],
  // A3: elbow housing with the wrist motors behind it, reaching to a4 at (0.3, 0, 0.05).
  elbow: [
    box(0.55, 0.3, 0.28, 0.02, 0, 0.03),
    cylY(0.15, 0.34, 0, 0, 0),
    box(0.2, 0.24, 0.22, -0.32, 0, 0.05),
  ],
  // A4 → A5: the 0.95 m forearm, tapering, ending in the wrist fork.
  forearm: [
    cylX(0.12, 0, 0.75, 0, 0, 0.09),
    box(0.22, 0.04, 0.16, 0.86, 0.1, 0),
    box(0.22, 0.04, 0.16, 0.86, -0.1, 0),
  ],
  // A5: the wrist body between the fork, reaching to a6.
  wrist: [cylY(0.075, 0.16, 0, 0, 0), cylX(0.07, 0, 0.17, 0, 0, 0.06)],
  // A6: the flange and a generic tool (a spindle) out to the TCP, 0.18 m beyond the flange.
  flange: [
    cylX(0.07, 0, 0.03),
    cylX(0.05, 0.03, 0.12),
    cylX(0.025, 0.12, 0.165, 0, 0, 0.01),
    cylX(0.006, 0.165, 0.18),
  ],
};

for (const [name, parts] of Object.entries(MESHES)) writeStl(OUT_DIR, name, parts);
