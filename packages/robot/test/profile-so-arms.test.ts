/**
 * The shipped SO-101 and SO-100 (LeRobot's arms, imported from PyPI's example-robot-data):
 * each profile parses and builds its chain to the tool, Feetech ids 1–6 as LeRobot numbers
 * them, the gripper jogged but outside the IK chain, and meshes light enough for a web page.
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { meshTriangles } from '../src/index.ts';
import { MODELS, loadRobot } from './numeric-fixtures.ts';

const JOINTS = ['shoulder_pan', 'shoulder_lift', 'elbow_flex', 'wrist_flex', 'wrist_roll'];

describe.each([
  ['so101', 'gripper_frame_link'],
  ['so100', 'tcp'],
])('the shipped %s', (name, tip) => {
  const { profile, chain, urdf } = loadRobot(name);

  test('servos 1–6 as LeRobot numbers them; the chain ends at the tool, the gripper beyond it', () => {
    expect(profile.servos.map((s) => [s.id, s.joint])).toEqual(
      [...JOINTS, 'gripper'].map((j, i) => [i + 1, j]),
    );
    expect(profile.ik.tipLink).toBe(tip);
    expect(chain.joints.map((j) => j.name)).toEqual(JOINTS);
  });

  test('every mesh its URDF names is there, under 300 KB and 10 000 triangles', () => {
    const meshes = [...urdf.matchAll(/filename="([^"]+)"/g)].map((m) => m[1]!);
    expect(meshes.length).toBeGreaterThan(5);
    for (const m of new Set(meshes)) {
      const bytes = fs.readFileSync(path.join(MODELS, name, m));
      expect(bytes.length, m).toBeLessThan(300_000);
      expect(meshTriangles('stl', bytes), m).toBeLessThan(10_000);
    }
  });
});
