/**
 * What a fitted thermal and electrical model (./thermal-model.ts) says a stretch of history
 * should have looked like, from its motion alone: each servo's temperature (the model run freely
 * from the first reported temperature, re-started after a gap) and supply voltage, and the power
 * the arm's motion drew. Pure.
 *
 * Power: the health frames carry no current, so it is read from the sag, as a bench meter would
 * across the supply's own resistance R: the motion draws I = (V₀ − V)/R at the voltage V left,
 * P = V·I. V₀ and the sag are the fitted model's, R (`supplyOhms`) is declared (the supply's
 * internal resistance and its common wiring). The same formula over the reported voltages gives
 * the measured power, so the two lines differ exactly where the voltage does not sag as the
 * motion says it should.
 */
import { simulateTrace, type ThermalTrace } from './thermal-fit.ts';
import { predictVolt, type ThermalParams } from './thermal-model.ts';

export interface ThermalPrediction {
  /** Temperature at each grid point, °C (NaN before the first report or across a gap). */
  temp: Float64Array;
  /** Supply voltage at each grid point, V (NaN where the arm's motion is unknown). */
  volt: Float64Array;
}

/** The arm's Σ|ω| around grid point k: the mean of the steps either side (as the fit takes it). */
function motionAround(total: ArrayLike<number> | undefined, k: number): number {
  if (!total) return NaN;
  const before = k > 0 ? total[k - 1]! : NaN;
  const after = k < total.length ? total[k]! : NaN;
  if (Number.isFinite(before) && Number.isFinite(after)) return (before + after) / 2;
  return Number.isFinite(before) ? before : after;
}

/** The model's temperature and voltage along a servo's trace. */
export function predictTrace(p: ThermalParams, trace: ThermalTrace): ThermalPrediction {
  const n = trace.temp.length;
  const volt = new Float64Array(n).fill(NaN);
  for (let k = 0; k < n; k++) {
    const s = motionAround(trace.totalSpeed, k);
    if (Number.isFinite(s)) volt[k] = predictVolt(p, s);
  }
  return { temp: simulateTrace(p, trace), volt };
}

/** Power drawn by the motion at supply voltage `voltV`, W: V·(V₀ − V)/R, never below 0. */
export function motionPowerW(volt0V: number, voltV: number, supplyOhms: number): number {
  if (!(supplyOhms > 0) || !Number.isFinite(voltV) || !Number.isFinite(volt0V)) return NaN;
  return Math.max(0, (voltV * (volt0V - voltV)) / supplyOhms);
}

/**
 * The arm's motion power at each grid point from the servos' voltages (`volts[i][k]`, measured or
 * predicted) and their fitted rest voltages: the servos' mean voltage against their mean V₀
 * (the supply is common; each servo's lead only shifts its own reading). NaN where no servo
 * has a voltage.
 */
export function armPowerW(
  volt0V: readonly number[],
  volts: readonly ArrayLike<number>[],
  supplyOhms: number,
): Float64Array {
  const n = volts.reduce((m, v) => Math.max(m, v.length), 0);
  const out = new Float64Array(n).fill(NaN);
  for (let k = 0; k < n; k++) {
    let v = 0;
    let v0 = 0;
    let count = 0;
    volts.forEach((series, i) => {
      const x = series[k];
      if (x !== undefined && Number.isFinite(x) && Number.isFinite(volt0V[i]!)) {
        v += x;
        v0 += volt0V[i]!;
        count++;
      }
    });
    if (count > 0) out[k] = motionPowerW(v0 / count, v / count, supplyOhms);
  }
  return out;
}
