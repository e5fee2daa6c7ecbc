/**
 * Puts a thermal model fitted by the middleware (`/history/thermal-model`, @armtwin/api) into
 * the store's `ThermalWatch`, servo by servo (matched by id), and says in words what the
 * predictions now rest on. Pure but for the watch it is given.
 */
import type { ThermalModelAnswer } from '@armtwin/api';
import type { ServoSpec } from '@armtwin/ik';
import { DEFAULT_THERMAL_PARAMS, type ThermalWatch } from '@armtwin/thermal';

/**
 * The history the HUD fits its models from (the middleware's range syntax) and its name: long
 * enough to hold some work and some rest, short enough for 50 ms angle windows (the path of quick
 * reversals) in the middleware's bound (apps/middleware/src/history/README.md).
 */
export const THERMAL_FIT_START = '-15m';
export const THERMAL_FIT_SPAN_WORDS = 'the last 15 minutes';

export interface ThermalFitSummary {
  /** Servos whose model now comes from the arm's history. */
  fitted: number;
  /** One sentence for the Health panel. */
  text: string;
}

export function applyThermalFit(
  watch: ThermalWatch,
  servos: readonly ServoSpec[],
  answer: ThermalModelAnswer,
): ThermalFitSummary {
  let fitted = 0;
  const why = new Set<string>();
  servos.forEach((spec, i) => {
    const fit = answer.servos.find((s) => Number(s.id) === spec.id);
    if (fit?.fitted) {
      watch.setParams(i, fit.params);
      fitted++;
    } else why.add(fit ? fit.reason : 'no history');
  });
  const all = servos.length;
  const text =
    fitted === 0
      ? `Thermal model: generic (${[...why].join('; ') || 'no history'}).`
      : `Thermal model: fitted from ${THERMAL_FIT_SPAN_WORDS} of history for ${fitted === all ? 'every servo' : `${fitted} of ${all} servos`}.`;
  return { fitted, text };
}

/** Back to the generic model for every servo (another arm, or before a new fit). */
export function resetThermalFit(watch: ThermalWatch): void {
  for (let i = 0; i < watch.count; i++) watch.setParams(i, DEFAULT_THERMAL_PARAMS);
}
