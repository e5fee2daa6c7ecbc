/**
 * A servo's thermal and electrical model, first order, in the units the arm reports (°C, V,
 * degrees of servo angle per second). Pure.
 *
 *   dT/dt = (restC + gainCPerDegS·|ω| − T) / tauS
 *
 * i.e. dT/dt = (P_in − (T − T_ambient)/R) / C with P_in = hold + a·|ω| folded into `restC`
 * (where the servo settles holding its pose) and `gainCPerDegS` (the steady rise per deg/s of
 * motion), and R·C = `tauS`. The supply each servo sees sags with the motion of the whole arm:
 *
 *   V = volt0V − sagVPerDegS · Σ|ω|   (Σ over every servo of the arm)
 *
 * so the power drawn by the arm's motion is read from the sag. A stalled servo pushing against
 * a jam heats with no motion at all: the model has no term for it, and that is how
 * `ThermalWatch` (./thermal-watch.ts) tells a stall, a dragging gear or an overheat fault from
 * hard work.
 */

export interface ThermalParams {
  /** Thermal time constant, s (R·C). */
  tauS: number;
  /** Where the servo settles at rest holding its pose, °C (ambient + the hold's rise). */
  restC: number;
  /** Steady-state rise per deg/s of the servo's own motion, °C per (deg/s). */
  gainCPerDegS: number;
  /** Supply at this servo with the arm at rest, V. */
  volt0V: number;
  /** Sag of that supply per deg/s of the whole arm's motion, V per (deg/s). */
  sagVPerDegS: number;
}

/**
 * A generic servo, used until a fit from the arm's history exists: a minute's time constant,
 * 35 °C at rest, a rise of 0.1 °C per deg/s (a hobby servo running flat out at 300 deg/s settles
 * about 30 °C above rest), 7.4 V with no sag.
 */
export const DEFAULT_THERMAL_PARAMS: ThermalParams = {
  tauS: 60,
  restC: 35,
  gainCPerDegS: 0.1,
  volt0V: 7.4,
  sagVPerDegS: 0,
};

/** The model's rate of temperature change at temperature `tempC` moving at `speedDegS`, °C/s. */
export function thermalRate(p: ThermalParams, tempC: number, speedDegS: number): number {
  return (p.restC + p.gainCPerDegS * Math.abs(speedDegS) - tempC) / p.tauS;
}

/** The temperature after `dtS` seconds at a constant speed (exact for the first-order model). */
export function stepTemperature(
  p: ThermalParams,
  tempC: number,
  speedDegS: number,
  dtS: number,
): number {
  const steady = p.restC + p.gainCPerDegS * Math.abs(speedDegS);
  return steady + (tempC - steady) * Math.exp(-dtS / p.tauS);
}

/** The supply voltage the model predicts at a servo while the whole arm moves at `totalDegS`. */
export function predictVolt(p: ThermalParams, totalDegS: number): number {
  return p.volt0V - p.sagVPerDegS * totalDegS;
}

/**
 * Seconds until `limitC` at a constant rate of `rateCPerS` from `tempC`: 0 at or past it,
 * Infinity when not heating.
 */
export function secondsTo(limitC: number, tempC: number, rateCPerS: number): number {
  if (tempC >= limitC) return 0;
  return rateCPerS > 0 ? (limitC - tempC) / rateCPerS : Infinity;
}
