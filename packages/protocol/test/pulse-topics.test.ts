import { describe, expect, it } from 'vitest';
import {
  angleFromPwm,
  armTopics,
  isValidArmId,
  normalisedPwm,
  parseTopic,
  pwmFromAngle,
  temperatureLevel,
  topic,
  voltageLevel,
} from '../src/index.ts';

describe('pulse width ↔ angle (§2)', () => {
  it('maps 270° onto 500–2500 µs around 1500', () => {
    expect(pwmFromAngle(0)).toBe(1500);
    expect(pwmFromAngle(135)).toBe(2500);
    expect(pwmFromAngle(-135)).toBe(500);
    expect(pwmFromAngle(1)).toBe(1507); // 7.407 µs per degree
    expect(pwmFromAngle(90, -1)).toBe(833);
    expect(angleFromPwm(2500)).toBeCloseTo(135, 12);
    expect(angleFromPwm(833, -1)).toBeCloseTo(90.045, 3);
    expect(normalisedPwm(500)).toBe(0);
    expect(normalisedPwm(2500)).toBe(1);
  });

  it('round-trips every pulse width through the angle', () => {
    for (let pwm = 500; pwm <= 2500; pwm++) {
      expect(pwmFromAngle(angleFromPwm(pwm, -1), -1)).toBe(pwm);
    }
  });
});

describe('topics (§3)', () => {
  it('builds and parses arm topics', () => {
    expect(armTopics('arm1')).toMatchObject({
      control: 'arm/arm1/control',
      status: 'arm/arm1/status',
      online: 'arm/arm1/online',
      operator: 'arm/arm1/operator',
    });
    expect(parseTopic('arm/cell-7/status')).toEqual({ armId: 'cell-7', kind: 'status' });
  });

  it.each(['', 'Arm1', 'arm/1', 'a'.repeat(33), 'arm 1', '../x', '<script>', '+', '#'])(
    'rejects arm id %j',
    (id) => {
      expect(isValidArmId(id)).toBe(false);
      expect(() => topic(id, 'status')).toThrow(/invalid arm id/);
      expect(parseTopic(`arm/${id}/status`)).toBeNull();
    },
  );

  it('ignores foreign topics', () => {
    expect(parseTopic('arm/arm1/unknown')).toBeNull();
    expect(parseTopic('robot/arm1/status')).toBeNull();
    expect(parseTopic('arm/arm1/status/extra')).toBeNull();
  });
});

describe('health thresholds (§5)', () => {
  it.each([
    [59.9, 'normal'],
    [60, 'warning'],
    [75, 'warning'],
    [75.1, 'critical'],
  ] as const)('%s °C is %s', (t, level) => expect(temperatureLevel(t)).toBe(level));
  it('below 6.5 V is critical', () => {
    expect(voltageLevel(6.5)).toBe('normal');
    expect(voltageLevel(6.49)).toBe('critical');
  });
});
