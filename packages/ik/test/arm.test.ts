import { describe, expect, it } from 'vitest';
import {
  DEMO_ARM,
  findServo,
  isWithinLimits,
  jointsFromServoAngles,
  pwmFromJoints,
  servoAnglesFromJoints,
  servoLimitsPwm,
  type ServoSpec,
} from '../src/index.ts';
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';

describe('pulse width ↔ angle (§2)', () => {
  it('is 2000/270 ≈ 7.407 µs per degree around 1500 µs', () => {
    expect(pwmFromAngle(100, 1) - 1500).toBe(741);
    expect(pwmFromAngle(0, 1)).toBe(1500);
    expect(pwmFromAngle(1, 1)).toBe(1507);
    expect(pwmFromAngle(10, 1)).toBe(1574);
    expect(pwmFromAngle(135, 1)).toBe(2500);
    expect(pwmFromAngle(-135, 1)).toBe(500);
    expect(pwmFromAngle(90, 1)).toBe(2167);
    expect(pwmFromAngle(90, -1)).toBe(833);
  });

  it('angleFromPwm inverts it, with polarity', () => {
    expect(angleFromPwm(2500, 1)).toBe(135);
    expect(angleFromPwm(2500, -1)).toBe(-135);
    expect(angleFromPwm(1574, 1)).toBeCloseTo(9.99, 2);
    for (let pwm = 500; pwm <= 2500; pwm++) {
      expect(pwmFromAngle(angleFromPwm(pwm, 1), 1)).toBe(pwm);
      expect(pwmFromAngle(angleFromPwm(pwm, -1), -1)).toBe(pwm);
    }
  });
});

describe('DEMO_ARM', () => {
  it('declares the six servos with §4 names, links and limits', () => {
    expect(DEMO_ARM.links).toEqual({ l0: 100, l1: 105, l2: 98, l3: 150 });
    expect(DEMO_ARM.servos.map((s) => [s.id, s.name, s.minDeg, s.maxDeg, s.polarity])).toEqual([
      [0, 'Base', -135, 135, 1],
      [1, 'Shoulder', -90, 90, 1],
      [2, 'Elbow', -135, 135, 1],
      [3, 'Wrist pitch', -90, 90, 1],
      [4, 'Wrist roll', -135, 135, 1],
      [5, 'Gripper', 0, 90, 1],
    ]);
    for (const s of DEMO_ARM.servos) expect(s.maxSpeedDegPerS).toBe(375);
  });

  it('servoLimitsPwm gives the pulse range of the angle limits, ordered for either polarity', () => {
    const pwm = DEMO_ARM.servos.map((s) => servoLimitsPwm(s));
    expect(pwm).toEqual([
      { min: 500, max: 2500 },
      { min: 833, max: 2167 },
      { min: 500, max: 2500 },
      { min: 833, max: 2167 },
      { min: 500, max: 2500 },
      { min: 1500, max: 2167 },
    ]);
    const flipped: ServoSpec = { ...DEMO_ARM.servos[5]!, polarity: -1 };
    expect(servoLimitsPwm(flipped)).toEqual({ min: 833, max: 1500 });
  });

  it('isWithinLimits checks a pulse against the servo, by number or wire id', () => {
    expect(isWithinLimits(1, 2167)).toBe(true);
    expect(isWithinLimits('001', 2168)).toBe(false);
    expect(isWithinLimits(5, 1499)).toBe(false);
    expect(isWithinLimits('005', 1500)).toBe(true);
    expect(isWithinLimits(6, 1500)).toBe(false);
    expect(isWithinLimits('1', 1500)).toBe(false);
    expect(isWithinLimits(0, NaN)).toBe(false);
    expect(findServo('003')?.name).toBe('Wrist pitch');
  });
});

describe('joints ↔ servo angles ↔ pulses', () => {
  const joints = { q0: 30, theta5: 120, theta4: -45, theta3: 10 };

  it('s000 = q0, s001 = θ5 − 90, s002 = θ4, s003 = θ3, and back', () => {
    const s = servoAnglesFromJoints(joints);
    expect(s).toEqual([30, 30, -45, 10]);
    expect(jointsFromServoAngles(s)).toEqual(joints);
  });

  it('pwmFromJoints applies §2 to each servo angle', () => {
    expect(pwmFromJoints(joints)).toEqual([1722, 1722, 1167, 1574]);
    expect(pwmFromJoints({ q0: 0, theta5: 90, theta4: 0, theta3: 0 })).toEqual([
      1500, 1500, 1500, 1500,
    ]);
  });
});
