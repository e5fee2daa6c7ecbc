/**
 * The URDF against the contract: parse public/models/armtwin5/armtwin5.urdf with urdf-loader in
 * node (visuals off, so no mesh is fetched) and check joint limits against DEMO_ARM, and the
 * tip link's world position against forwardKinematics for random poses (within 0.5 mm).
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import { parseUrdf } from './support/parseUrdf.ts';
import { DEMO_ARM, forwardKinematics, jointsFromServoAngles, type Quad } from '@armtwin/ik';

/** The URDF joint each servo 000–005 drives (its value: the servo angle s of §2, in radians). */
const SERVO_JOINTS = ['base_yaw', 'shoulder', 'elbow', 'wrist_pitch', 'wrist_roll', 'gripper'];
/** The link whose origin is the gripper tip (tool centre point). */
const TIP_LINK = 'tip';
const jointValueFromAngle = (deg: number): number => (deg * Math.PI) / 180;

const URDF_FILE = path.resolve(
  fileURLToPath(import.meta.url),
  '../../../../public/models/armtwin5/armtwin5.urdf',
);
const MESH_DIR = path.join(path.dirname(URDF_FILE), 'meshes');

let robot: URDFRobot;

beforeAll(() => {
  robot = parseUrdf(fs.readFileSync(URDF_FILE, 'utf8'));
});

/** Deterministic pseudo-random numbers (mulberry32), so a failure reproduces. */
function rng(seed: number): () => number {
  let a = seed;
  return () => {
    a = (a + 0x6d2b79f5) | 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function tipMm(): THREE.Vector3 {
  robot.updateMatrixWorld(true);
  const tip = robot.links[TIP_LINK];
  if (!tip) throw new Error('no tip link');
  return tip.getWorldPosition(new THREE.Vector3()).multiplyScalar(1000);
}

describe('armtwin5.urdf', () => {
  it('has one revolute joint per servo, with the servo limits of DEMO_ARM', () => {
    SERVO_JOINTS.forEach((name, id) => {
      const joint = robot.joints[name];
      const spec = DEMO_ARM.servos[id]!;
      expect(joint?.jointType, name).toBe('revolute');
      expect(joint!.limit.lower).toBeCloseTo(jointValueFromAngle(spec.minDeg), 9);
      expect(joint!.limit.upper).toBeCloseTo(jointValueFromAngle(spec.maxDeg), 9);
    });
  });

  it('puts the tip at home (0, 0, 453) with every servo at its centre', () => {
    for (const name of SERVO_JOINTS) robot.joints[name]!.setJointValue(0);
    const tip = tipMm();
    expect(tip.x).toBeCloseTo(0, 6);
    expect(tip.y).toBeCloseTo(0, 6);
    expect(tip.z).toBeCloseTo(453, 6);
  });

  it('puts the tip where forwardKinematics says, for 500 random poses within the limits', () => {
    const random = rng(5);
    for (let n = 0; n < 500; n++) {
      const s = DEMO_ARM.servos.map((spec) => spec.minDeg + random() * (spec.maxDeg - spec.minDeg));
      SERVO_JOINTS.forEach((name, id) =>
        robot.joints[name]!.setJointValue(jointValueFromAngle(s[id]!)),
      );
      const fk = forwardKinematics(jointsFromServoAngles(s.slice(0, 4) as Quad));
      const tip = tipMm();
      const err = Math.hypot(tip.x - fk.x, tip.y - fk.y, tip.z - fk.z);
      expect(err, `pose ${s.map((v) => v.toFixed(1)).join(', ')}`).toBeLessThan(0.5);
    }
  });

  it('references meshes that exist and are binary STL', () => {
    const text = fs.readFileSync(URDF_FILE, 'utf8');
    const files = [...text.matchAll(/filename="meshes\/([^"]+)"/g)].map((m) => m[1]!);
    expect(files.length).toBeGreaterThanOrEqual(6);
    for (const file of new Set(files)) {
      const bytes = fs.readFileSync(path.join(MESH_DIR, file));
      const triangles = bytes.readUInt32LE(80);
      expect(bytes.length, file).toBe(84 + triangles * 50);
    }
  });
});
