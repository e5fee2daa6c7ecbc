/**
 * The thermal model of @armtwin/protocol against the simulated servos, in sim time: a model
 * fitted from five minutes of the arm's own reports (rounded to 1 °C at 2 Hz as the firmware
 * sends them) recovers the sim's constants, raises no warning over another five minutes of
 * ordinary work, and warns of a stall at least 10 s before the servo reports 60 °C.
 * tests/integration/thermal-model.test.ts does the same through MQTT and InfluxDB.
 */
import { describe, expect, test } from 'vitest';
import { TEMP_WARNING_C, type Frame } from '@armtwin/protocol';
import {
  fitThermal,
  thermalTraces,
  ThermalWatch,
  type ServoSamples,
  type ThermalParams,
  type TimedValue,
} from '@armtwin/thermal';
import { applyFault, NO_FAULTS, type Fault } from '../src/faults.ts';
import { SimModel } from '../src/model.ts';
import { DEFAULT_SIM_MODEL_OPTIONS, type SimModelOptions } from '../src/options.ts';

const T0 = 1_700_000_000_000;
const TICK_MS = 20; // 50 Hz state
const HEALTH_MS = 500; // 2 Hz health

/** The sim's own constants in the model's terms, servo i (see options.ts and servos.ts). */
function truth(o: SimModelOptions, i: number): ThermalParams {
  const vmax = o.arm.servos[i]!.maxSpeedDegPerS;
  return {
    tauS: o.thermalTauMs / 1000,
    restC: o.ambientC + o.degPerAmp * o.holdAmps[i]!,
    gainCPerDegS: (o.degPerAmp * o.moveAmps) / vmax,
    volt0V: 0, // not compared
    sagVPerDegS: (o.supplyOhms * o.moveAmps) / vmax,
  };
}

/**
 * Ordinary work: spells of random moves of every servo, spells of sweeping back and forth at top
 * speed (the hardest work the arm does: it warms ~20 °C), and pauses.
 */
function script(seed: number, seconds: number): { at: number; frame: Frame }[] {
  let x = seed;
  const rand = () => (x = (x * 1664525 + 1013904223) >>> 0) / 2 ** 32;
  const out: { at: number; frame: Frame }[] = [];
  let at = 1000;
  while (at < seconds * 1000) {
    const kind = rand();
    const spell = 15_000 + Math.floor(rand() * 30_000);
    const end = Math.min(at + spell, seconds * 1000);
    if (kind < 0.35) {
      for (let side = 1; at < end; at += 400, side = -side)
        for (let id = 0; id < 5; id++)
          out.push({ at, frame: { type: 'angleMove', id, deg: side * 60, ms: 0 } });
    } else if (kind < 0.75) {
      for (; at < end; at += 2000 + Math.floor(rand() * 4000))
        for (let id = 0; id < 6; id++) {
          if (rand() < 0.3) continue;
          const deg = id === 5 ? rand() * 60 : -60 + rand() * 120;
          const ms = 300 + Math.floor(rand() * 2500);
          out.push({ at, frame: { type: 'angleMove', id, deg, ms } });
        }
    }
    at = end;
  }
  return out;
}

type Samples = { [K in keyof ServoSamples]: TimedValue[] };

interface Run {
  samples: Samples[];
  events: { t: number; i: number; event: string }[];
  /** When each servo first reported ≥ 60 °C (NaN: never). */
  crossed: number[];
  t: number;
}

/** Runs the sim from `t` for `seconds`, reporting to `watch` as the runner would. */
function drive(
  model: SimModel,
  t: number,
  seconds: number,
  frames: { at: number; frame: Frame }[],
  watch?: ThermalWatch,
  until?: (r: Run) => boolean,
): Run {
  const n = model.servos.count;
  const run: Run = {
    samples: Array.from({ length: n }, () => ({ temp: [], volt: [], angle: [] })),
    events: [],
    crossed: new Array<number>(n).fill(NaN),
    t,
  };
  const end = t + seconds * 1000;
  let next = 0;
  const start = t;
  const out: string[] = [];
  for (; t <= end; t += TICK_MS) {
    while (next < frames.length && start + frames[next]!.at <= t)
      model.execute(frames[next++]!.frame, t, out);
    model.advance(t);
    for (let i = 0; i < n; i++) {
      const a = model.angleAt(i, t);
      run.samples[i]!.angle.push({ t, v: a });
      watch?.position(i, a);
    }
    if ((t - T0) % HEALTH_MS === 0) {
      for (let i = 0; i < n; i++) {
        const temp = Math.round(model.servos.temp[i]!);
        run.samples[i]!.temp.push({ t, v: temp });
        run.samples[i]!.volt.push({ t, v: Math.round(model.servos.takeMinMv(i)) / 1000 });
        const e = watch?.health(i, t, temp);
        if (e) run.events.push({ t, i, event: e });
        if (temp >= TEMP_WARNING_C && Number.isNaN(run.crossed[i]!)) run.crossed[i] = t;
      }
      run.t = t;
      if (until?.(run)) break;
    }
  }
  run.t = t;
  return run;
}

function fitted(options: Partial<SimModelOptions> = {}): {
  params: ThermalParams[];
  model: SimModel;
  t: number;
} {
  const model = new SimModel(options, T0);
  const r = drive(model, T0, 300, script(1, 300));
  const traces = thermalTraces(r.samples, T0, r.t, 1000);
  const params = traces.map((tr) => fitThermal(tr).params);
  return { params, model, t: r.t };
}

describe('the thermal model on the simulated arm (sim time)', () => {
  const { params, model, t: trained } = fitted();
  const o = DEFAULT_SIM_MODEL_OPTIONS;

  test('a fit from five minutes of reports recovers the sim constants of the busy servos', () => {
    for (const i of [1, 2]) {
      const p = params[i]!;
      const tr = truth(o, i);
      console.log(
        `servo ${i}: τ ${p.tauS.toFixed(1)} s (sim ${tr.tauS}), rest ${p.restC.toFixed(2)} °C (sim ${tr.restC}), ` +
          `gain ${p.gainCPerDegS.toFixed(4)} °C/(deg/s) (sim ${tr.gainCPerDegS.toFixed(4)}), ` +
          `sag ${(p.sagVPerDegS * 1000).toFixed(3)} mV/(deg/s) (sim ${(tr.sagVPerDegS * 1000).toFixed(3)})`,
      );
      expect(Math.abs(p.tauS - tr.tauS) / tr.tauS).toBeLessThan(0.2);
      expect(Math.abs(p.restC - tr.restC)).toBeLessThan(1.5);
      expect(Math.abs(p.gainCPerDegS - tr.gainCPerDegS) / tr.gainCPerDegS).toBeLessThan(0.2);
    }
  });

  test('five more minutes of ordinary work raise no warning; a stall warns ≥ 10 s before 60 °C', () => {
    const watch = new ThermalWatch(params);
    const normal = drive(model, trained, 300, script(2, 300), watch);
    expect(normal.events).toEqual([]);

    // A minute's rest (the shoulder cools to where it holds), then servo 001 jams and the next
    // command makes it push against the jam. (Jammed still hot from the sweeps, near 45 °C, it
    // reaches 60 °C in about 9 s: no warning could come 10 s ahead of that.)
    const rest = drive(model, normal.t + TICK_MS, 60, [], watch);
    expect(rest.events).toEqual([]);
    const t = rest.t + TICK_MS;
    const stall: Fault = { fault: 'stall', id: 1 };
    applyFault(model, { ...NO_FAULTS }, stall, t, o.overheatC);
    const push = [{ at: 0, frame: { type: 'angleMove', id: 1, deg: -20, ms: 1000 } as Frame }];
    const r = drive(model, t, 60, push, watch, (x) => !Number.isNaN(x.crossed[1]!));
    const raised = r.events.find((e) => e.i === 1 && e.event === 'raised');
    expect(raised).toBeDefined();
    const lead = r.crossed[1]! - raised!.t;
    console.log(
      `stall: warned ${(raised!.t - t) / 1000} s after the stall, ${lead / 1000} s before 60 °C`,
    );
    expect(lead).toBeGreaterThanOrEqual(10_000);
    expect(r.events.filter((e) => e.i !== 1)).toEqual([]);
  });

  test('an overheat fault warns before 60 °C; a gradual one (a dragging gear) ≥ 10 s before', () => {
    for (const overheatTauMs of [o.overheatTauMs, 40_000]) {
      const { params: p, model: m, t } = fitted({ overheatTauMs });
      const watch = new ThermalWatch(p);
      drive(m, t, 30, [], watch);
      const at = t + 30_000 + TICK_MS;
      applyFault(m, { ...NO_FAULTS }, { fault: 'overheat', id: 2 }, at, o.overheatC);
      const r = drive(m, at, 120, [], watch, (x) => !Number.isNaN(x.crossed[2]!));
      const raised = r.events.find((e) => e.i === 2 && e.event === 'raised');
      expect(raised).toBeDefined();
      const lead = r.crossed[2]! - raised!.t;
      console.log(
        `overheat (τ ${overheatTauMs / 1000} s): warned ${lead / 1000} s before 60 °C (reached ${(r.crossed[2]! - at) / 1000} s after the fault)`,
      );
      expect(lead).toBeGreaterThan(0);
      if (overheatTauMs >= 40_000) expect(lead).toBeGreaterThanOrEqual(10_000);
    }
  });
});
