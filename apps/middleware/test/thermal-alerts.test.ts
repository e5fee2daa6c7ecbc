/**
 * The middleware's thermal watch over status payloads as an arm sends them: a stall (heat with
 * no motion) raises one warning for that servo and clears when the heating stops; ordinary
 * motion the fitted model explains raises none; the stored line is an `audit` point of the
 * arm's log; each arm is due for a fit when new and again after `refitMs`.
 */
import { describe, expect, test } from 'vitest';
import type { ThermalModelAnswer } from '@armtwin/api';
import { encodeFrame } from '@armtwin/protocol';
import {
  parseThermalAlert,
  stepTemperature,
  type ThermalAlert,
  type ThermalParams,
} from '@armtwin/thermal';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';
import { SeriesClock } from '../src/points.ts';
import { ThermalAlerts, thermalAlertLine } from '../src/thermal-alerts.ts';

const T0 = 1_700_000_000_000;
const enc = new TextEncoder();
const status = (t: number, frames: string) =>
  enc.encode(encodeFrame({ type: 'time', ms: t }) + frames);
const health = (id: number, temp: number) =>
  encodeFrame({ type: 'health', id, temp: Math.round(temp), mv: 7400 });
const position = (id: number, pwm: number) =>
  encodeFrame({ type: 'position', id, pwm: Math.round(pwm) });

const PARAMS: ThermalParams = {
  tauS: 20,
  restC: 34,
  gainCPerDegS: 0.06,
  volt0V: 7.4,
  sagVPerDegS: 0,
};
const fit = (arm: string): ThermalModelAnswer => ({
  arm,
  start: 0,
  stop: 0,
  stepMs: 1000,
  times: [],
  power: { supplyOhms: 0.3, measuredW: [], predictedW: [] },
  servos: ['000', '001'].map((id) => ({
    id,
    params: PARAMS,
    fitted: true,
    tauFitted: true,
    intervals: 100,
    r2: 0.98,
    rmseC: 0.3,
    voltRmseV: 0.01,
    reason: '',
    predicted: { temp: [], volt: [] },
  })),
});

describe('ThermalAlerts', () => {
  test('a stall raises one warning for that servo, stored in the log, cleared when it stops', () => {
    const heat = new ThermalAlerts();
    const clock = new SeriesClock();
    const events: ThermalAlert[] = [];
    let t = T0;
    let temp = 34;
    const step = (rate: number) => {
      t += 500;
      temp += rate * 0.5;
      events.push(
        ...heat.handle(
          'arm/a1/status',
          status(t, position(0, 1500) + health(0, 34) + health(1, temp)),
          t,
        ),
      );
    };
    for (let k = 0; k < 20; k++) step(0); // rest
    expect(events).toEqual([]);
    for (let k = 0; k < 16; k++) step(2.5); // stalled: 2.5 °C/s with no motion
    expect(events.map((e) => [e.kind, e.id])).toEqual([['thermal-warning', '001']]);
    const e = events[0]!;
    expect(e.excessCPerS).toBeGreaterThan(1.5);
    expect(e.secondsToLimit).toBeGreaterThan(5);
    expect(e.detail).toMatch(
      /^servo 001 heats \d\.\d °C\/s faster than its model allows: 60 °C in about \d+ s/,
    );
    expect(parseThermalAlert(JSON.stringify(e))).toEqual(e);
    const line = thermalAlertLine('a1', e, clock);
    expect(line).toBe(
      `audit,arm=a1,kind=thermal-warning by="thermal model",detail="${e.detail}" ${e.at * 1000}`,
    );
    for (let k = 0; k < 20; k++) step(-0.3); // freed: it cools as the model expects
    expect(events.map((x) => x.kind)).toEqual(['thermal-warning', 'thermal-cleared']);
  });

  test('hard work the fitted model explains raises no warning', () => {
    const heat = new ThermalAlerts();
    heat.handle('arm/a2/status', status(T0, health(1, 34)), T0);
    heat.setFit('a2', fit('a2'), T0);
    let t = T0;
    let temp = 34;
    let side = 1;
    let peak = temp;
    const events: ThermalAlert[] = [];
    // Sweeps of ±60° every 0.4 s (300 deg/s) for 60 s, then a minute's rest.
    for (let k = 0; k < 600; k++) {
      t += 200;
      const moving = k < 300;
      if (moving && k % 2 === 0) side = -side;
      const speed = moving ? 300 : 0;
      temp = stepTemperature(PARAMS, temp, speed, 0.2);
      peak = Math.max(peak, temp);
      const pwm = 1500 + (moving ? side * 667 : 0);
      const frames = position(1, pwm) + (k % 5 === 0 ? health(1, temp) : '');
      events.push(...heat.handle('arm/a2/status', status(t, frames), t));
    }
    expect(peak).toBeGreaterThan(45); // it did warm
    expect(events).toEqual([]);
  });

  test("fed the ingest's decoded frames, it raises what it raises from the payloads", () => {
    const byPayload = new ThermalAlerts();
    const byFrames = new ThermalAlerts();
    const ingest = new Ingest(new Metrics());
    ingest.onStatusFrames = (arm, frames) => got.push(...byFrames.frames(arm, frames, t));
    const want: ThermalAlert[] = [];
    const got: ThermalAlert[] = [];
    let t = T0;
    for (let k = 0; k < 60; k++) {
      t += 500;
      const temp = 34 + (k < 20 ? 0 : 1.25 * (k - 20)); // rest, then a stall
      const payload = status(t, `{${position(0, 1500)}${health(0, 34)}${health(1, temp)}}`);
      want.push(...byPayload.handle('arm/a1/status', payload, t));
      ingest.handle('arm/a1/status', payload, t);
    }
    expect(want.map((e) => e.kind)).toEqual(['thermal-warning']);
    expect(got).toEqual(want);
  });

  test('only status topics of valid arms are watched; new arms are due for a fit at once', () => {
    const heat = new ThermalAlerts({ refitMs: 60_000 });
    expect(heat.handle('arm/a3/control', status(T0, health(1, 90)), T0)).toEqual([]);
    expect(heat.handle('arm/BAD!/status', status(T0, health(1, 90)), T0)).toEqual([]);
    expect(heat.dueForFit(T0)).toEqual([]);
    heat.handle('arm/a3/status', status(T0, health(1, 34)), T0);
    expect(heat.dueForFit(T0)).toEqual(['a3']);
    expect(heat.setFit('a3', fit('a3'), T0)).toBe(1); // servo 001 reported; 000 not yet
    expect(heat.watchOf('a3', 1)?.params(0)).toEqual(PARAMS);
    expect(heat.dueForFit(T0 + 59_000)).toEqual([]);
    expect(heat.dueForFit(T0 + 60_000)).toEqual(['a3']);
  });
});
