/**
 * The early warning's wire form (`arm/{id}/alert`) and the model's prediction along a trace:
 * the electrical part (power read from the sag) and the voltage the motion should leave.
 */
import { describe, expect, test } from 'vitest';
import {
  armPowerW,
  motionPowerW,
  parseThermalAlert,
  predictTrace,
  thermalAlert,
  thermalAlertTopic,
  type ThermalParams,
  type ThermalState,
} from '../src/index.ts';

const STATE: ThermalState = {
  measuredC: 41.23,
  predictedC: 34.9,
  measuredRate: 2.1,
  modelRate: 0.04,
  unexplainedRate: 2.06,
  secondsToLimit: 8.94,
  speedDegS: 0,
  warning: true,
  warnedAt: 1000,
};

describe('thermal alerts on the wire', () => {
  test('an event says which servo, how much faster than the model, and how soon 60 °C', () => {
    const e = thermalAlert('thermal-warning', 1, 1_700_000_000_123.4, STATE);
    expect(thermalAlertTopic('arm1')).toBe('arm/arm1/alert');
    expect(e).toEqual({
      at: 1_700_000_000_123,
      kind: 'thermal-warning',
      id: '001',
      tempC: 41.2,
      predictedC: 34.9,
      excessCPerS: 2.06,
      secondsToLimit: 8.9,
      detail:
        'servo 001 heats 2.1 °C/s faster than its model allows: 60 °C in about 9 s (now 41 °C, model 35 °C)',
    });
    expect(parseThermalAlert(JSON.stringify(e))).toEqual(e);
    const cleared = thermalAlert('thermal-cleared', 12, 5, { ...STATE, secondsToLimit: Infinity });
    expect(cleared.secondsToLimit).toBeNull();
    expect(cleared.detail).toBe(
      'servo 012 heats as its model allows again (now 41 °C, model 35 °C)',
    );
    expect(parseThermalAlert(JSON.stringify(cleared))).toEqual(cleared);
  });

  test('anything else is not an alert', () => {
    const good = thermalAlert('thermal-warning', 1, 1, STATE);
    for (const bad of [
      'not json',
      '42',
      'null',
      JSON.stringify({ ...good, kind: 'e-stop' }),
      JSON.stringify({ ...good, id: '1' }),
      JSON.stringify({ ...good, tempC: 'hot' }),
      JSON.stringify({ ...good, secondsToLimit: 'soon' }),
    ])
      expect(parseThermalAlert(bad)).toBeNull();
  });
});

describe('the model along a trace', () => {
  const P: ThermalParams = {
    tauS: 20,
    restC: 30,
    gainCPerDegS: 0.1,
    volt0V: 7.4,
    sagVPerDegS: 0.002,
  };

  test('voltage sags with the arm’s motion; temperature runs from the first report', () => {
    const trace = {
      stepS: 1,
      temp: [30, NaN, NaN, NaN],
      speed: [100, 100, 0],
      totalSpeed: [300, 300, 0],
    };
    const p = predictTrace(P, trace);
    expect(p.volt[0]).toBeCloseTo(7.4 - 0.6, 9);
    expect(p.volt[2]).toBeCloseTo(7.4 - 0.3, 9); // half a step moving, half at rest
    expect(p.volt[3]).toBeCloseTo(7.4, 9);
    expect(p.temp[0]).toBe(30);
    expect(p.temp[1]).toBeCloseTo(40 - 10 * Math.exp(-1 / 20), 9);
    expect(p.temp[2]!).toBeGreaterThan(p.temp[1]!);
  });

  test('power is read from the sag: P = V·(V₀ − V)/R, per arm from the servos’ mean', () => {
    expect(motionPowerW(7.4, 6.8, 0.3)).toBeCloseTo((6.8 * 0.6) / 0.3, 9); // 2 A at 6.8 V
    expect(motionPowerW(7.4, 7.5, 0.3)).toBe(0);
    expect(motionPowerW(7.4, 7, 0)).toBeNaN();
    const w = armPowerW(
      [7.4, 7.2],
      [
        [6.8, NaN],
        [6.6, NaN],
      ],
      0.3,
    );
    expect(w[0]).toBeCloseTo((6.7 * 0.6) / 0.3, 9);
    expect(w[1]).toBeNaN();
  });
});
