/**
 * public/models/armtwin5/profile.json against the contract: it agrees with DEMO_ARM (servos,
 * limits, polarity, speeds, §4 offsets and links), with the URDF's joint names and limits, and
 * its chain (built from the URDF) has §4's forward kinematics.
 */
import { describe, expect, it } from 'vitest';
import {
  armProfileFromProfile,
  jointFromServo,
  jointLimits,
  parseUrdfJoints,
  posePwm,
  servoTable,
} from '../src/index.ts';
import {
  DEMO_ARM,
  chainFk,
  forwardKinematics,
  jointsFromServoAngles,
  servoLimitsPwm,
  type Quad,
} from '@armtwin/ik';
import { loadRobot, rng } from './numeric-fixtures.ts';

const { profile, chain, urdf } = loadRobot('armtwin5');

describe('armtwin5 profile', () => {
  it('is DEMO_ARM: same servos, limits, polarity, speeds, §4 offsets and link lengths', () => {
    const arm = armProfileFromProfile(profile);
    expect(profile.ik.kind).toBe('analytic5');
    expect(arm?.links).toEqual(DEMO_ARM.links);
    expect(arm?.servos).toEqual(DEMO_ARM.servos);
  });

  it("gives the simulator DEMO_ARM's pulse limits and speed, home at 1500 µs", () => {
    servoTable(profile).forEach((row, i) => {
      const spec = DEMO_ARM.servos[i]!;
      expect(row.id).toBe(spec.id);
      expect({ min: row.minPwm, max: row.maxPwm }).toEqual(servoLimitsPwm(spec));
      expect(row.maxSpeedPwmPerS).toBeCloseTo((spec.maxSpeedDegPerS * 2000) / 270, 9);
      expect(row.homePwm).toBe(1500);
    });
    expect(posePwm(profile, 'open')?.[5]).toBe(2167);
  });

  it("names the URDF's joints, with the URDF's limits", () => {
    const parsed = parseUrdfJoints(urdf);
    if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
    for (const servo of profile.servos) {
      const joint = parsed.joints.find((j) => j.name === servo.joint);
      expect(joint?.type, servo.joint).toBe('revolute');
      const lim = jointLimits(servo);
      expect(joint!.lower).toBeCloseTo(lim.min, 12);
      expect(joint!.upper).toBeCloseTo(lim.max, 12);
      expect(joint!.velocity).toBeCloseTo((servo.maxSpeed * Math.PI) / 180, 9);
    }
    expect(parsed.links).toContain(profile.ik.baseLink);
    expect(parsed.links).toContain(profile.ik.tipLink);
    expect(chain.joints.map((j) => j.name)).toEqual([
      'base_yaw',
      'shoulder',
      'elbow',
      'wrist_pitch',
      'wrist_roll',
    ]);
  });

  it("has §4's forward kinematics: chain FK (from the URDF) = forwardKinematics within 1e-9 mm", () => {
    const next = rng(11);
    for (let k = 0; k < 200; k++) {
      const s = profile.servos.slice(0, 5).map((sv) => sv.min + next() * (sv.max - sv.min));
      const q = chain.joints.map((j) =>
        jointFromServo(profile.servos[j.servoIndex]!, s[j.servoIndex]!),
      );
      const tip = chainFk(chain, q);
      const p = forwardKinematics(jointsFromServoAngles(s.slice(0, 4) as Quad));
      expect(Math.hypot(tip[12]! - p.x, tip[13]! - p.y, tip[14]! - p.z)).toBeLessThan(1e-9);
    }
  });
});
