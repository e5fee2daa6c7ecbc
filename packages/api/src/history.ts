/**
 * The answers of the middleware's history API (apps/middleware/src/history/README.md): the
 * middleware writes them, the HUD reads them. Times are epoch ms. Every answer carries `arm`,
 * `start`, `stop`.
 */

export interface RangeEcho {
  arm: string;
  start: number;
  stop: number;
}

/**
 * The fields `/history/series?field=` serves; `command` is the commanded angle (measurement
 * `command`, field `angle`), so commanded and actual can be overlaid.
 */
export const HISTORY_FIELDS = ['pwm', 'angle', 'temp', 'volt', 'command'] as const;
export type HistoryField = (typeof HISTORY_FIELDS)[number];
/** The fields the HUD charts (`pwm` is served but not charted). */
export type SeriesField = Exclude<HistoryField, 'pwm'>;

export interface Series {
  id: string;
  /** Epoch ms, ascending. */
  times: number[];
  values: number[];
}

export interface SeriesAnswer extends RangeEcho {
  field: HistoryField;
  every: string;
  everyMs: number;
  series: Series[];
}

export interface PoseAnswer extends RangeEcho {
  every: string;
  everyMs: number;
  /** Servo ids, the order of each frame's angles. */
  ids: string[];
  /** Frame times, ascending. */
  times: number[];
  /** angles[frame][i] belongs to ids[i]; null before that servo's first sample. */
  angles: (number | null)[][];
}

export const ALARM_KINDS = ['temp-warning', 'temp-critical', 'undervoltage'] as const;
export type AlarmKind = (typeof ALARM_KINDS)[number];

export interface AlarmEpisode {
  kind: AlarmKind;
  arm: string;
  id: string;
  start: number;
  /** null: still in the alarm state at the end of the range. */
  end: number | null;
  /** Highest temperature (°C) or lowest voltage (V). */
  peak: number;
}

export interface AlarmsAnswer extends RangeEcho {
  truncated: boolean;
  episodes: AlarmEpisode[];
}

export interface TrackingJoint {
  id: string;
  /** Actual samples compared. */
  samples: number;
  /** Mean absolute error, degrees (null with no samples). */
  meanAbsError: number | null;
  /** Maximum absolute error, degrees, and the time (epoch ms) it happened. */
  maxAbsError: number | null;
  maxAt: number | null;
}

export interface TrackingAnswer extends RangeEcho {
  unit: 'deg';
  /**
   * null: every actual sample in range was compared. Otherwise more than the bound were there,
   * and the first sample of each window of this many ms was compared (the true maximum may be missed).
   */
  thinnedEveryMs: number | null;
  truncated: boolean;
  joints: TrackingJoint[];
}

/** One control event as stored (PROTOCOL § Control, `arm/{id}/audit`): who did what, when. */
export interface AuditRecord {
  /** Epoch ms. */
  at: number;
  /** The user it came from; '' = the plain control topic (no log-in). */
  by: string;
  /** `taken`, `granted`, `refused-command`, … (`AUDIT_KINDS` in @armtwin/protocol). */
  kind: string;
  /** A sentence for people. */
  detail: string;
}

/** `/history/audit`: the arm's control events in range, in time order. */
export interface AuditAnswer extends RangeEcho {
  truncated: boolean;
  events: AuditRecord[];
}

/** Every error answer of the history API: `{error}` with a 4xx or 5xx status. */
export interface ErrorAnswer {
  error: string;
}

/**
 * One servo's thermal and electrical model as `/history/thermal-model` fitted it from the range
 * (the model of @armtwin/protocol's thermal-model.ts):
 * dT/dt = (restC + gainCPerDegS·|ω| − T) / tauS and V = volt0V − sagVPerDegS·Σ|ω|.
 */
export interface ThermalModelParams {
  /** Thermal time constant, s. */
  tauS: number;
  /** Where the servo settles at rest holding its pose, °C. */
  restC: number;
  /** Steady rise per deg/s of the servo's own motion, °C per (deg/s). */
  gainCPerDegS: number;
  /** Supply at the servo with the arm at rest, V. */
  volt0V: number;
  /** Supply sag per deg/s of the whole arm's motion, V per (deg/s). */
  sagVPerDegS: number;
}

export interface ThermalServoFit {
  id: string;
  params: ThermalModelParams;
  /** false: too little history in range; `params` are the generic prior (see `reason`). */
  fitted: boolean;
  /** false: the temperature hardly moved, so τ is the prior's. */
  tauFitted: boolean;
  /** Complete intervals of the grid used. */
  intervals: number;
  /** Fraction of the temperature changes explained (null: none). */
  r2: number | null;
  /** RMS error of the model run freely over the range, °C (null: none). */
  rmseC: number | null;
  /** RMS error of the supply model, V (null: no voltage). */
  voltRmseV: number | null;
  /** Why it is not (fully) fitted; '' when it is. */
  reason: string;
  /**
   * What the model says the range should have looked like from its motion alone, on the grid's
   * cell centres (`ThermalModelAnswer.times`): temperature run freely from the first report
   * (re-started after a gap), and supply voltage; null where it cannot say.
   */
  predicted: { temp: (number | null)[]; volt: (number | null)[] };
}

/**
 * The power the arm's motion drew, W, read from the supply's sag across `supplyOhms`
 * (@armtwin/protocol's thermal-predict.ts): from the reported voltages and from the model's.
 */
export interface ThermalPowerTrace {
  supplyOhms: number;
  measuredW: (number | null)[];
  predictedW: (number | null)[];
}

/** `/history/thermal-model`: every servo's model fitted from its history in range. */
export interface ThermalModelAnswer extends RangeEcho {
  /** Grid step the fit used, ms. */
  stepMs: number;
  /** The grid's cell centres, epoch ms: the times of every `predicted` and `power` value. */
  times: number[];
  servos: ThermalServoFit[];
  power: ThermalPowerTrace;
}
