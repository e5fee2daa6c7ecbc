import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  fitThermal,
  predictVolt,
  secondsTo,
  thermalTraces,
  stepTemperature,
  ThermalWatch,
  type ThermalParams,
  type ThermalTrace,
} from '../src/index.ts';

/** Speeds by grid step: rests and moves of random length and speed. */
function motion(steps: number, seed: number): number[] {
  let x = seed >>> 0 || 1;
  const rand = () => (x = (x * 1664525 + 1013904223) >>> 0) / 2 ** 32;
  const out: number[] = [];
  while (out.length < steps) {
    const len = 5 + Math.floor(rand() * 40);
    const speed = rand() < 0.4 ? 0 : rand() * 300;
    for (let k = 0; k < len && out.length < steps; k++) out.push(speed);
  }
  return out;
}

/** The true model run at fine steps, sampled every `stepS` (optionally rounded like §1 reports). */
function trace(p: ThermalParams, speeds: number[], stepS: number, round: boolean): ThermalTrace {
  const temp: number[] = [];
  let t = p.restC;
  const sub = 20;
  for (let k = 0; k <= speeds.length; k++) {
    temp.push(round ? Math.round(t) : t);
    for (let j = 0; j < sub && k < speeds.length; j++)
      t = stepTemperature(p, t, speeds[k]!, stepS / sub);
  }
  const total = speeds.map((s) => s * 2.5);
  // The supply at a report reflects the motion either side of it (as fitThermal reads it).
  const around = (k: number) =>
    k === 0 ? total[0]! : k >= total.length ? total[k - 1]! : (total[k - 1]! + total[k]!) / 2;
  const volt = temp.map((_, k) => predictVolt(p, around(k)));
  return { stepS, temp, speed: speeds, volt, totalSpeed: total };
}

const TRUE: ThermalParams = {
  tauS: 20,
  restC: 33.75,
  gainCPerDegS: 0.06,
  volt0V: 7.3,
  sagVPerDegS: 0.0007,
};

describe('fitThermal', () => {
  it('recovers τ, rest temperature, gain and the supply sag from exact synthetic history', () => {
    fc.assert(
      fc.property(
        fc.record({
          tauS: fc.double({ min: 8, max: 90, noNaN: true }),
          restC: fc.double({ min: 22, max: 45, noNaN: true }),
          gainCPerDegS: fc.double({ min: 0.04, max: 0.2, noNaN: true }),
          volt0V: fc.double({ min: 6, max: 12, noNaN: true }),
          sagVPerDegS: fc.double({ min: 0, max: 0.002, noNaN: true }),
        }),
        fc.integer({ min: 1, max: 2 ** 31 }),
        (p, seed) => {
          const tr = trace(p, motion(900, seed), 1, false);
          const temps = Array.from(tr.temp);
          fc.pre(Math.max(...temps) - Math.min(...temps) >= 3); // else τ is kept (next tests)
          const fit = fitThermal(tr);
          expect(fit.fitted).toBe(true);
          expect(fit.tauFitted).toBe(true);
          expect(Math.abs(fit.params.tauS - p.tauS) / p.tauS).toBeLessThan(0.05);
          expect(Math.abs(fit.params.restC - p.restC)).toBeLessThan(0.5);
          expect(Math.abs(fit.params.gainCPerDegS - p.gainCPerDegS) / p.gainCPerDegS).toBeLessThan(
            0.05,
          );
          expect(fit.params.volt0V).toBeCloseTo(p.volt0V, 3);
          expect(fit.params.sagVPerDegS).toBeCloseTo(p.sagVPerDegS, 5);
          expect(fit.rmseC).toBeLessThan(0.5);
        },
      ),
      { numRuns: 40 },
    );
  });

  it('stays close with reports rounded to 1 °C at 2 Hz, as the arm sends them', () => {
    const fit = fitThermal(trace(TRUE, motion(1200, 7), 0.5, true));
    expect(Math.abs(fit.params.tauS - TRUE.tauS) / TRUE.tauS).toBeLessThan(0.15);
    expect(Math.abs(fit.params.restC - TRUE.restC)).toBeLessThan(1);
    expect(Math.abs(fit.params.gainCPerDegS - TRUE.gainCPerDegS) / TRUE.gainCPerDegS).toBeLessThan(
      0.15,
    );
    expect(fit.rmseC).toBeLessThan(1);
  });

  it('skips intervals with gaps instead of bridging them', () => {
    const tr = trace(TRUE, motion(600, 3), 1, false);
    const temp = Array.from(tr.temp);
    for (let k = 200; k < 260; k++) temp[k] = NaN;
    const fit = fitThermal({ ...tr, temp });
    expect(fit.intervals).toBeLessThan(600 - 60);
    expect(Math.abs(fit.params.tauS - TRUE.tauS) / TRUE.tauS).toBeLessThan(0.05);
  });

  it('gives the prior, saying why, when there is too little history', () => {
    const fit = fitThermal(trace(TRUE, motion(10, 1), 1, false));
    expect(fit.fitted).toBe(false);
    expect(fit.reason).toMatch(/fewer than 20/);
    expect(fit.params.tauS).toBe(60);
  });

  it('keeps τ from the prior when the servo never warmed or cooled', () => {
    const still = trace(TRUE, new Array<number>(300).fill(0), 1, false);
    const fit = fitThermal(still);
    expect(fit.fitted).toBe(true);
    expect(fit.tauFitted).toBe(false);
    expect(fit.params.tauS).toBe(60);
    expect(fit.params.restC).toBeCloseTo(TRUE.restC, 1);
    expect(fit.reason).toMatch(/too small to fit τ/);
  });
});

/** Feeds a watch the way the arm reports: positions at 50 Hz, health (rounded) at 2 Hz. */
function run(
  watch: ThermalWatch,
  p: ThermalParams,
  seconds: number,
  speedAt: (s: number) => number,
  extraHeat: (s: number) => number,
  start = { t: 0, temp: p.restC, angle: 0 },
) {
  let { t, temp, angle } = start;
  const events: { t: number; event: string }[] = [];
  let crossed = NaN;
  const dt = 0.02;
  for (let k = 0; k < seconds / dt; k++) {
    const s = t / 1000;
    const v = speedAt(s);
    temp = stepTemperature(p, temp, v, dt) + extraHeat(s) * dt;
    angle += v * dt * (Math.floor(s / 3) % 2 ? -1 : 1);
    t += dt * 1000;
    watch.position(0, angle);
    if (Math.round(t) % 500 === 0) {
      const e = watch.health(0, Math.round(t), Math.round(temp));
      if (e) events.push({ t, event: e });
      if (Number.isNaN(crossed) && Math.round(temp) >= 60) crossed = t;
    }
  }
  return { events, crossed, end: { t, temp, angle } };
}

describe('ThermalWatch', () => {
  it('raises nothing when the heat is explained by hard motion', () => {
    const watch = new ThermalWatch([TRUE]);
    // Flat out for 30 s, rests, flat out again: the servo heats at up to 1 °C/s.
    const r = run(
      watch,
      TRUE,
      180,
      (s) => (s % 60 < 30 ? 375 : 0),
      () => 0,
    );
    expect(r.events).toEqual([]);
    expect(watch.state(0)!.warning).toBe(false);
  });

  it('warns of a stall at least 10 s before 60 °C, and clears once it is freed', () => {
    const watch = new ThermalWatch([TRUE]);
    const calm = run(
      watch,
      TRUE,
      30,
      () => 0,
      () => 0,
    );
    // Stalled: 2 A more, 50 °C more at steady state, no motion.
    const stall = run(
      watch,
      { ...TRUE, restC: TRUE.restC + 50 },
      30,
      () => 0,
      () => 0,
      calm.end,
    );
    const raised = stall.events.find((e) => e.event === 'raised');
    expect(raised).toBeDefined();
    expect(stall.crossed - raised!.t).toBeGreaterThanOrEqual(10_000);
    const freed = run(
      watch,
      TRUE,
      60,
      () => 0,
      () => 0,
      stall.end,
    );
    expect(freed.events.map((e) => e.event)).toEqual(['cleared']);
  });

  it('does not warn of a slow drift that would take longer than the horizon to reach 60 °C', () => {
    const watch = new ThermalWatch([TRUE], { horizonS: 30, marginCPerS: 0.2 });
    const r = run(
      watch,
      TRUE,
      20,
      () => 0,
      () => 0.25,
      { t: 0, temp: 30, angle: 0 },
    );
    expect(r.events).toEqual([]);
  });

  it('predicts the temperature from the motion: the dashed line follows a healthy servo', () => {
    const watch = new ThermalWatch([TRUE]);
    run(
      watch,
      TRUE,
      120,
      (s) => (s % 40 < 20 ? 300 : 0),
      () => 0,
    );
    const st = watch.state(0)!;
    expect(Math.abs(st.predictedC - st.measuredC)).toBeLessThan(1.5);
  });

  it('ignores repeated and out-of-order reports and non-numbers', () => {
    const watch = new ThermalWatch([TRUE]);
    expect(watch.health(0, 1000, 30)).toBeNull();
    expect(watch.health(0, 1000, 90)).toBeNull();
    expect(watch.health(0, 500, 90)).toBeNull();
    expect(watch.health(0, 1500, NaN)).toBeNull();
    expect(watch.health(5, 1500, 30)).toBeNull();
    expect(watch.state(0)!.measuredC).toBe(30);
  });
});

describe('secondsTo', () => {
  it('is 0 past the limit and Infinity when cooling', () => {
    expect(secondsTo(60, 61, 1)).toBe(0);
    expect(secondsTo(60, 40, -1)).toBe(Infinity);
    expect(secondsTo(60, 40, 2)).toBe(10);
  });
});

describe('thermalTraces', () => {
  it('takes temperatures at the cell centres, the path between them, and leaves gaps empty', () => {
    const temp = [0, 500, 1000, 1500, 6000, 6500].map((t) => ({ t, v: 30 + t / 1000 }));
    // Back and forth 10° every 250 ms: 40 deg/s of path though the mean position hardly moves.
    const angle = Array.from({ length: 29 }, (_, k) => ({ t: k * 250, v: k % 2 ? 10 : 0 }));
    const volt = [
      { t: 100, v: 7.2 },
      { t: 600, v: 7.0 },
    ];
    const [tr] = thermalTraces([{ temp, volt, angle }], 0, 7000, 1000);
    expect(Array.from(tr!.temp).slice(0, 3)).toEqual([30.5, 31.5, NaN]);
    expect(tr!.temp[5]).toBeNaN(); // between reports 4.5 s apart
    expect(tr!.temp[6]).toBe(36.5); // a report right at the centre
    expect(Array.from(tr!.speed).slice(0, 6)).toEqual([40, 40, 40, 40, 40, 40]);
    expect(tr!.volt![0]).toBeCloseTo(7.1, 9);
    expect(Array.from(tr!.totalSpeed!).slice(0, 2)).toEqual([40, 40]);
  });
});
