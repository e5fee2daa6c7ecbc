/**
 * public/models/track6: the profile names the URDF's 7 joints with its limits and speeds, the
 * URDF's meshes exist and are small binary STL files, and the kinematics have the intended
 * proportions (zero pose, a 3 m track, ~2.7 m arm reach).
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import {
  chainJointsFromPose,
  jointLimits,
  parseUrdfJoints,
  pwmFromChainJoints,
  servoTable,
} from '../src/index.ts';
import { chainFk } from '@armtwin/ik';
import { MODELS, loadRobot } from './numeric-fixtures.ts';

const { profile, chain, urdf } = loadRobot('track6');
const DIR = path.join(MODELS, 'track6');

describe('track6 profile and URDF', () => {
  it("maps servos 000–006 to the URDF's joints, with its limits and speeds", () => {
    const parsed = parseUrdfJoints(urdf);
    if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
    expect(profile.servos.map((s) => s.key)).toEqual([
      '000',
      '001',
      '002',
      '003',
      '004',
      '005',
      '006',
    ]);
    for (const servo of profile.servos) {
      const joint = parsed.joints.find((j) => j.name === servo.joint);
      expect(joint?.type, servo.joint).toBe(servo.type);
      const lim = jointLimits(servo);
      expect(joint!.lower).toBeCloseTo(lim.min, 12);
      expect(joint!.upper).toBeCloseTo(lim.max, 12);
      const speed =
        servo.type === 'revolute' ? (servo.maxSpeed * Math.PI) / 180 : servo.maxSpeed / 1000;
      expect(joint!.velocity).toBeCloseTo(speed, 9);
    }
    expect(chain.dof).toBe(7);
    expect(profile.ik).toEqual({ kind: 'numeric', baseLink: 'rail', tipLink: 'tcp' });
  });

  it('references meshes that exist as small binary STL files', () => {
    const files = [...urdf.matchAll(/filename="([^"]+)"/g)].map((m) => m[1]!);
    expect(files.length).toBe(8);
    for (const file of files) {
      const buf = fs.readFileSync(path.join(DIR, file));
      expect(buf.length, file).toBeLessThan(200_000);
      // Binary STL: 80-byte header, triangle count, 50 bytes per triangle.
      expect(buf.length, file).toBe(84 + 50 * buf.readUInt32LE(80));
    }
  });

  it('puts the tool centre point where the proportions say, and its tool axis along +x, at zero', () => {
    const tip = chainFk(chain, new Float64Array(7));
    // x: a2 offset 0.35 + a4 0.3 + forearm 0.95 + wrist 0.2 + tool 0.18; z: 0.25 + 0.35 + 0.4 + 1.15 + 0.05.
    expect(tip[12]).toBeCloseTo(1980, 9);
    expect(tip[13]).toBeCloseTo(0, 9);
    expect(tip[14]).toBeCloseTo(2200, 9);
    expect([tip[8], tip[9], tip[10]].map((v) => Math.round(v! * 1e9) / 1e9)).toEqual([1, 0, 0]);
    const atEnd = chainFk(chain, [3, 0, 0, 0, 0, 0, 0]);
    expect(atEnd[12]! - tip[12]!).toBeCloseTo(3000, 9);
  });

  it('round-trips named poses through chain joints and pulses', () => {
    const ready = chainJointsFromPose(profile, chain, 'ready')!;
    expect(ready[0]).toBeCloseTo(1.5, 12);
    const pwm = pwmFromChainJoints(profile, chain, ready);
    expect(pwm[0]).toBe(1500);
    expect(pwm[3]).toBe(1500 + Math.round((15 * 2000) / 270)); // a3 = 30° with offset 15° → s = 15°
    expect(servoTable(profile).map((s) => s.homePwm)).toEqual([
      500, 1500, 1500, 1389, 1500, 1500, 1500,
    ]);
  });
});
