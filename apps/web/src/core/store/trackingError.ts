/**
 * Tracking error: how far each joint is from where it was commanded to be, for painting the
 * arm's links (scene/TrackingPaint.ts) and the legend (Ghost panel). "Commanded" is the
 * command's course at the instant of the joint's newest report (the predictor's idea of where
 * the controller is taking it, ./JointPredictor.ts), so a joint moving as commanded reads ~0°
 * and a lagging or blocked one grows; without a course, the pulse this HUD commanded, once the
 * joint has stopped moving. Colour ramp and thresholds are declared once, here. Pure.
 */

export interface TrackingPaintOptions {
  /** Below this error a joint tracks (ok colour), degrees. */
  okDeg: number;
  /** From this error on, a joint is off its command (error colour), degrees. */
  errorDeg: number;
  /** The ramp: ok below okDeg, warn → error between okDeg and errorDeg, error above. RGB hex. */
  colours: { ok: number; warn: number; error: number };
}

export const DEFAULT_TRACKING_PAINT_OPTIONS: TrackingPaintOptions = {
  okDeg: 2,
  errorDeg: 5,
  colours: { ok: 0x22c55e, warn: 0xf59e0b, error: 0xef4444 },
};

export const TRACKING_LEVELS = ['none', 'ok', 'warn', 'error'] as const;
export type TrackingLevel = (typeof TRACKING_LEVELS)[number];

/** 'on' / 'off' as the user set it; 'auto' paints while something has been commanded. */
export type TrackingPaintSetting = 'auto' | 'on' | 'off';

export function trackingLevel(
  errDeg: number,
  o: TrackingPaintOptions = DEFAULT_TRACKING_PAINT_OPTIONS,
): TrackingLevel {
  if (!Number.isFinite(errDeg)) return 'none';
  return errDeg < o.okDeg ? 'ok' : errDeg < o.errorDeg ? 'warn' : 'error';
}

const lerp = (a: number, b: number, t: number, shift: number) =>
  Math.round(((a >> shift) & 255) + (((b >> shift) & 255) - ((a >> shift) & 255)) * t) << shift;

/** The ramp's colour for an error (RGB hex); -1 for no error known. */
export function trackingColour(
  errDeg: number,
  o: TrackingPaintOptions = DEFAULT_TRACKING_PAINT_OPTIONS,
): number {
  if (!Number.isFinite(errDeg)) return -1;
  const { ok, warn, error } = o.colours;
  if (errDeg < o.okDeg) return ok;
  if (errDeg >= o.errorDeg) return error;
  // Quantised to tenths, so a colour changes (and the scene redraws) only for a visible step.
  const t = Math.round(((errDeg - o.okDeg) / (o.errorDeg - o.okDeg)) * 10) / 10;
  return lerp(warn, error, t, 16) | lerp(warn, error, t, 8) | lerp(warn, error, t, 0);
}

/** Each joint's tracking error, level and colour, and whether the arm is painted. */
export class TrackingErrors {
  readonly opts: TrackingPaintOptions;
  /** |commanded − reported| per servo, degrees; NaN where nothing was commanded. */
  errorDeg: Float64Array;
  /** The commanded angle each error was taken against, degrees (NaN = none). */
  commandedDeg: Float64Array;
  levels: TrackingLevel[];
  colours: Int32Array;
  setting: TrackingPaintSetting = 'auto';
  /** Some joint has a commanded angle. */
  anyCommanded = false;
  /** Bumped when a level or colour changed. */
  version = 0;

  constructor(servoCount: number, opts: Partial<TrackingPaintOptions> = {}) {
    this.opts = { ...DEFAULT_TRACKING_PAINT_OPTIONS, ...opts };
    this.errorDeg = new Float64Array(servoCount).fill(NaN);
    this.commandedDeg = new Float64Array(servoCount).fill(NaN);
    this.levels = new Array<TrackingLevel>(servoCount).fill('none');
    this.colours = new Int32Array(servoCount).fill(-1);
  }

  /** The user's switch: painted ('on') or not ('off') whatever was commanded. */
  setSetting(setting: TrackingPaintSetting): void {
    this.setting = setting;
  }

  /** Whether the arm's links are painted now. */
  get active(): boolean {
    return this.setting === 'on' || (this.setting === 'auto' && this.anyCommanded);
  }

  /** Joint i's commanded and reported angles (degrees, NaN = unknown); true if its paint changed. */
  set(i: number, commandedDeg: number, reportedDeg: number): boolean {
    const err = Math.abs(commandedDeg - reportedDeg);
    this.commandedDeg[i] = commandedDeg;
    this.errorDeg[i] = err;
    if (Number.isFinite(commandedDeg)) this.anyCommanded = true;
    const level = trackingLevel(err, this.opts);
    const colour = trackingColour(err, this.opts);
    if (level === this.levels[i] && colour === this.colours[i]) return false;
    this.levels[i] = level;
    this.colours[i] = colour;
    this.version++;
    return true;
  }

  reset(): void {
    this.errorDeg.fill(NaN);
    this.commandedDeg.fill(NaN);
    this.levels.fill('none');
    this.colours.fill(-1);
    this.anyCommanded = false;
    this.version++;
  }
}
