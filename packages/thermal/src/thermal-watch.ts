/**
 * The live side of the thermal model: fed each servo's positions and health reports as they
 * arrive, it keeps the model's predicted temperature beside the measured one and raises an
 * early warning when a servo heats faster than its motion explains, before the 60 °C threshold
 * of §5. Pure: times are arguments (epoch ms), nothing is read from a clock.
 *
 * Each health report closes an interval: the servo's mean |speed| over it (from the position
 * reports inside it) drives the model. Over the last `windowS` the measured rate is the
 * least-squares slope of the reported temperatures, the model's rate the mean of what the model
 * allows over the same intervals. The difference is heat the motion does not explain (a stall
 * pushing against a jam, a dragging gear, a failing driver). A warning is raised when it stays
 * above `marginCPerS` for `sustainS` while, at the measured rate, the servo would reach `limitC`
 * within `horizonS`; it clears after `clearS` below half the margin.
 */
import { TEMP_WARNING_C } from '@armtwin/protocol';
import { secondsTo, stepTemperature, thermalRate, type ThermalParams } from './thermal-model.ts';

export interface ThermalWatchOptions {
  /** Span of the measured and model rates, s. */
  windowS: number;
  /** Fewest health reports in the window for a rate. */
  minSamples: number;
  /** Heating beyond the model's rate that counts, °C/s. */
  marginCPerS: number;
  /** How long it must last before a warning, s. */
  sustainS: number;
  /** How long below half the margin before a warning clears, s. */
  clearS: number;
  /** Warn only when the measured rate would reach `limitC` within this, s. */
  horizonS: number;
  /** The threshold warned of, °C (§5). */
  limitC: number;
  /**
   * How fast the predicted temperature is pulled towards the measured one, per s: slow enough
   * that a fault shows as the two lines parting, fast enough that a model a little off does not
   * drift away for good.
   */
  observerPerS: number;
  /** Reports further apart than this, s, start afresh (a break in the data says no rate). */
  maxGapS: number;
}

export const DEFAULT_THERMAL_WATCH_OPTIONS: ThermalWatchOptions = {
  windowS: 4,
  minSamples: 5,
  marginCPerS: 0.6,
  sustainS: 1,
  clearS: 5,
  horizonS: 300,
  limitC: TEMP_WARNING_C,
  observerPerS: 1 / 120,
  maxGapS: 5,
};

/** One servo's state after its latest health report. */
export interface ThermalState {
  /** The latest reported temperature, °C (NaN before the first). */
  measuredC: number;
  /** The model's temperature now, °C (NaN before the first report). */
  predictedC: number;
  /** Measured rate over the window, °C/s (NaN until the window has enough reports). */
  measuredRate: number;
  /** What the model allows over the same window, °C/s. */
  modelRate: number;
  /** measuredRate − modelRate: heat the motion does not explain, °C/s. */
  unexplainedRate: number;
  /** Seconds to `limitC` at the measured rate (Infinity when not heating). */
  secondsToLimit: number;
  /** The servo's mean |speed| over the last interval, deg/s. */
  speedDegS: number;
  warning: boolean;
  /** When the current warning was raised, epoch ms (NaN when none). */
  warnedAt: number;
}

/** What a health report changed: a warning raised or cleared, or nothing. */
export type ThermalEvent = 'raised' | 'cleared' | null;

interface Sample {
  t: number;
  temp: number;
  /** The model's rate over the interval ending here, °C/s (NaN for the first). */
  rate: number;
  dt: number;
}

/** A servo's state before its first report. */
const freshThermalState = (): ThermalState => ({
  measuredC: NaN,
  predictedC: NaN,
  measuredRate: NaN,
  modelRate: NaN,
  unexplainedRate: NaN,
  secondsToLimit: Infinity,
  speedDegS: 0,
  warning: false,
  warnedAt: NaN,
});

class ServoWatch {
  readonly state: ThermalState = freshThermalState();
  private samples: Sample[] = [];
  private lastAngle = NaN;
  private path = 0;
  private overSince = NaN;
  private calmSince = NaN;

  constructor(public params: ThermalParams) {}

  position(angleDeg: number): void {
    if (Number.isFinite(this.lastAngle)) this.path += Math.abs(angleDeg - this.lastAngle);
    this.lastAngle = angleDeg;
  }

  health(t: number, tempC: number, o: ThermalWatchOptions): ThermalEvent {
    const s = this.state;
    const last = this.samples[this.samples.length - 1];
    if (last && t - last.t > o.maxGapS * 1000) {
      // After a break: the warning stays; the rates and the prediction start afresh.
      this.samples = [];
      this.path = 0;
      this.overSince = NaN;
    }
    const prev = this.samples[this.samples.length - 1];
    const dt = prev ? (t - prev.t) / 1000 : 0;
    if (prev && !(dt > 0)) return null; // out of order or repeated: ignored
    const speed = dt > 0 ? this.path / dt : 0;
    this.path = 0;
    let rate = NaN;
    if (prev) {
      rate = thermalRate(this.params, (prev.temp + tempC) / 2, speed);
      const p = stepTemperature(this.params, s.predictedC, speed, dt);
      s.predictedC = p + (tempC - p) * (1 - Math.exp(-dt * o.observerPerS));
    } else s.predictedC = tempC;
    s.measuredC = tempC;
    s.speedDegS = speed;
    this.samples.push({ t, temp: tempC, rate, dt });
    const from = t - o.windowS * 1000;
    while (this.samples.length > 0 && this.samples[0]!.t < from) this.samples.shift();
    this.rates(o);
    return this.decide(t, o);
  }

  /** Least-squares slope of the window's temperatures and the model's mean rate over it. */
  private rates(o: ThermalWatchOptions): void {
    const s = this.state;
    const w = this.samples;
    if (w.length < o.minSamples) {
      s.measuredRate = s.modelRate = s.unexplainedRate = NaN;
      s.secondsToLimit = Infinity;
      return;
    }
    const t0 = w[0]!.t;
    let mt = 0;
    let mT = 0;
    for (const x of w) {
      mt += (x.t - t0) / 1000;
      mT += x.temp;
    }
    mt /= w.length;
    mT /= w.length;
    let num = 0;
    let den = 0;
    for (const x of w) {
      const dx = (x.t - t0) / 1000 - mt;
      num += dx * (x.temp - mT);
      den += dx * dx;
    }
    let rateSum = 0;
    let span = 0;
    for (let k = 1; k < w.length; k++) {
      rateSum += w[k]!.rate * w[k]!.dt;
      span += w[k]!.dt;
    }
    s.measuredRate = den > 0 ? num / den : NaN;
    s.modelRate = span > 0 ? rateSum / span : NaN;
    s.unexplainedRate = s.measuredRate - s.modelRate;
    s.secondsToLimit = secondsTo(o.limitC, s.measuredC, s.measuredRate);
  }

  private decide(t: number, o: ThermalWatchOptions): ThermalEvent {
    const s = this.state;
    const over = s.unexplainedRate > o.marginCPerS && s.secondsToLimit < o.horizonS;
    if (over) {
      this.calmSince = NaN;
      if (Number.isNaN(this.overSince)) this.overSince = t;
      if (!s.warning && t - this.overSince >= o.sustainS * 1000) {
        s.warning = true;
        s.warnedAt = t;
        return 'raised';
      }
      return null;
    }
    this.overSince = NaN;
    if (!s.warning) return null;
    if (!(s.unexplainedRate > o.marginCPerS / 2)) {
      if (Number.isNaN(this.calmSince)) this.calmSince = t;
      if (t - this.calmSince >= o.clearS * 1000) {
        s.warning = false;
        s.warnedAt = NaN;
        this.calmSince = NaN;
        return 'cleared';
      }
    } else this.calmSince = NaN;
    return null;
  }

  reset(): void {
    this.samples = [];
    this.lastAngle = NaN;
    this.path = 0;
    this.overSince = this.calmSince = NaN;
    Object.assign(this.state, freshThermalState());
  }
}

/** The watch over every servo of one arm, by servo index. */
export class ThermalWatch {
  readonly options: ThermalWatchOptions;
  private readonly servos: ServoWatch[];

  constructor(params: readonly ThermalParams[], options: Partial<ThermalWatchOptions> = {}) {
    this.options = { ...DEFAULT_THERMAL_WATCH_OPTIONS, ...options };
    this.servos = params.map((p) => new ServoWatch(p));
  }

  get count(): number {
    return this.servos.length;
  }

  /** The model of servo i from now on (e.g. a fit from the arm's history arrived). */
  setParams(i: number, params: ThermalParams): void {
    const w = this.servos[i];
    if (w) w.params = params;
  }

  params(i: number): ThermalParams | undefined {
    return this.servos[i]?.params;
  }

  /** A position report of servo i: its servo angle, degrees. */
  position(i: number, angleDeg: number): void {
    if (Number.isFinite(angleDeg)) this.servos[i]?.position(angleDeg);
  }

  /** A health report of servo i at `t` (epoch ms): what it changed. */
  health(i: number, t: number, tempC: number): ThermalEvent {
    const w = this.servos[i];
    if (!w || !Number.isFinite(tempC) || !Number.isFinite(t)) return null;
    return w.health(t, tempC, this.options);
  }

  state(i: number): ThermalState | undefined {
    return this.servos[i]?.state;
  }

  /** Forgets every report (a break in the data: rates across it would mean nothing). */
  reset(): void {
    for (const w of this.servos) w.reset();
  }
}
