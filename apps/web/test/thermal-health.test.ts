/**
 * The HUD's thermal model: the store feeds every position and health report to its
 * ThermalWatch, keeps the predicted temperature beside the measured one for the charts, raises
 * the early warning in words when a servo heats with no motion to explain it, and takes a fit
 * from the middleware's `/history/thermal-model` servo by servo.
 */
import { describe, expect, it } from 'vitest';
import type { ThermalModelAnswer, ThermalServoFit } from '@armtwin/api';
import { DEMO_ARM } from '@armtwin/ik';
import { encodeGroup, encodeHealth, encodePosition, encodeTime } from '@armtwin/protocol';
import { DEFAULT_THERMAL_PARAMS } from '@armtwin/thermal';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { thermalWarningWords } from '../src/core/store/healthWords.ts';
import { applyThermalFit, resetThermalFit } from '../src/core/store/thermalFit.ts';

const T0 = 1_700_000_000_000;
const PARAMS = { tauS: 20, restC: 34, gainCPerDegS: 0.06, volt0V: 7.3, sagVPerDegS: 0.0007 };

/** Health of every servo at `t`: the shoulder at `shoulder` °C, the rest at 30 °C. */
const health = (t: number, shoulder: number) =>
  encodeTime(t) +
  encodeGroup([0, 1, 2, 3, 4, 5].map((id) => encodeHealth(id, id === 1 ? shoulder : 30, 7300)));
const still = (t: number) =>
  encodeTime(t) + encodeGroup([0, 1, 2, 3, 4, 5].map((id) => encodePosition(id, 1500)));

function fit(id: string, fitted = true): ThermalServoFit {
  return {
    id,
    params: PARAMS,
    fitted,
    tauFitted: fitted,
    intervals: 100,
    r2: 0.9,
    rmseC: 0.3,
    voltRmseV: 0.01,
    reason: fitted ? '' : '3 complete intervals, fewer than 20',
    predicted: { temp: [], volt: [] },
  };
}

describe('ArmStore thermal model', () => {
  it('draws the prediction beside the measurement and warns of a servo heating with no motion', () => {
    const s = new ArmStore({ arm: DEMO_ARM });
    for (let i = 0; i < 6; i++) s.thermal.setParams(i, PARAMS);
    let temp = 34;
    let warnedAt = NaN;
    for (let k = 0; k < 60; k++) {
      const t = T0 + k * 500;
      s.ingest(still(t), k * 500);
      if (k >= 20) temp += 1.2; // heating 2.4 °C/s while holding still: a stall
      s.ingest(health(t, Math.round(temp)), k * 500 + 1);
      if (Number.isNaN(warnedAt) && s.thermal.state(1)!.warning) warnedAt = k;
    }
    expect(warnedAt).toBeGreaterThan(20);
    expect(warnedAt).toBeLessThan(30);
    const st = s.thermal.state(1)!;
    expect(st.predictedC).toBeLessThan(st.measuredC - 20); // the dashed line stayed low
    expect(s.history.predicted[1]!.latest()).toBeCloseTo(st.predictedC, 6);
    expect(s.history.predicted[0]!.latest()).toBeGreaterThan(29); // drawn for every servo
    expect(s.thermal.state(0)!.warning).toBe(false);
    expect(thermalWarningWords('Shoulder', st)).toMatch(
      /^Shoulder is heating \d+\.\d °C\/s, \d+\.\d °C\/s more than its motion explains: already at 60 °C\. Look for a jam or a load\.$/,
    );
    expect(thermalWarningWords('Base', s.thermal.state(0))).toBe('');
    s.resetArm();
    expect(s.thermal.state(1)!.warning).toBe(false);
    expect(s.history.predicted[1]!.length).toBe(0);
  });

  it('says how long until 60 °C while there is time', () => {
    const words = thermalWarningWords('Elbow', {
      measuredC: 40,
      predictedC: 31,
      measuredRate: 2,
      modelRate: 0.1,
      unexplainedRate: 1.9,
      secondsToLimit: 10,
      speedDegS: 0,
      warning: true,
      warnedAt: T0,
    });
    expect(words).toBe(
      'Elbow is heating 2.0 °C/s, 1.9 °C/s more than its motion explains: 60 °C in about 10 s. Look for a jam or a load.',
    );
  });
});

describe('applyThermalFit', () => {
  it('takes each fitted servo by id and says what the predictions rest on', () => {
    const s = new ArmStore({ arm: DEMO_ARM });
    const answer: ThermalModelAnswer = {
      arm: 'arm1',
      start: T0,
      stop: T0 + 3_600_000,
      stepMs: 1000,
      times: [],
      power: { supplyOhms: 0.3, measuredW: [], predictedW: [] },
      servos: [fit('001'), fit('000'), fit('002', false), fit('042')],
    };
    const r = applyThermalFit(s.thermal, DEMO_ARM.servos, answer);
    expect(r.fitted).toBe(2);
    expect(r.text).toBe(
      'Thermal model: fitted from the last 15 minutes of history for 2 of 6 servos.',
    );
    expect(s.thermal.params(0)).toEqual(PARAMS);
    expect(s.thermal.params(1)).toEqual(PARAMS);
    expect(s.thermal.params(2)).toEqual(DEFAULT_THERMAL_PARAMS);
    resetThermalFit(s.thermal); // another arm: never the last arm's fit
    expect(s.thermal.params(0)).toEqual(DEFAULT_THERMAL_PARAMS);
    const none = applyThermalFit(s.thermal, DEMO_ARM.servos, {
      ...answer,
      servos: [fit('003', false)],
    });
    expect(none.text).toBe(
      'Thermal model: generic (no history; 3 complete intervals, fewer than 20).',
    );
  });
});
