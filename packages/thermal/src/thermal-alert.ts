/**
 * The thermal model's early warnings on the wire (docs/protocol.md § A thermal model of each servo): the
 * middleware's `ThermalWatch` (./thermal-watch.ts) over each arm's status stream publishes one
 * JSON object on `arm/{id}/alert` (QoS 1, not retained) when a servo starts to heat faster than
 * its model allows and when it stops, and stores the same event in the arm's log (InfluxDB
 * measurement `audit`, kind `thermal-warning` / `thermal-cleared`). Pure.
 */
import type { ThermalState } from './thermal-watch.ts';

/** Early warnings, not retained (a late subscriber asks the history, not the broker). */
export const thermalAlertTopic = (armId: string): string => `arm/${armId}/alert`;

export const THERMAL_ALERT_KINDS = ['thermal-warning', 'thermal-cleared'] as const;
export type ThermalAlertKind = (typeof THERMAL_ALERT_KINDS)[number];

/** Who the stored event is from (`by` of the `audit` point). */
export const THERMAL_ALERT_BY = 'thermal model';

export interface ThermalAlert {
  /** When the watch decided, epoch ms (the health report's time). */
  at: number;
  kind: ThermalAlertKind;
  /** The servo, three digits. */
  id: string;
  /** Reported temperature, °C. */
  tempC: number;
  /** The model's temperature, °C. */
  predictedC: number;
  /** Heating the motion does not explain, °C/s. */
  excessCPerS: number;
  /** Seconds to the 60 °C threshold at the measured rate (null: not heating). */
  secondsToLimit: number | null;
  /** One sentence for logs and the History panel. */
  detail: string;
}

const id3 = (id: number): string => String(id).padStart(3, '0');
const round1 = (x: number): number => Math.round(x * 10) / 10;

/** The sentence of an event: what the servo does, against what the model allows. */
export function thermalAlertDetail(
  kind: ThermalAlertKind,
  id: string,
  tempC: number,
  predictedC: number,
  excessCPerS: number,
  secondsToLimit: number | null,
): string {
  const now = `now ${Math.round(tempC)} °C, model ${Math.round(predictedC)} °C`;
  if (kind === 'thermal-cleared') return `servo ${id} heats as its model allows again (${now})`;
  const when = secondsToLimit === null ? '' : `: 60 °C in about ${Math.round(secondsToLimit)} s`;
  return `servo ${id} heats ${excessCPerS.toFixed(1)} °C/s faster than its model allows${when} (${now})`;
}

/** The event of a watch's decision for servo `id` at `at`, from its state then. */
export function thermalAlert(
  kind: ThermalAlertKind,
  id: number,
  at: number,
  s: ThermalState,
): ThermalAlert {
  const toLimit = Number.isFinite(s.secondsToLimit) ? round1(s.secondsToLimit) : null;
  const excess = Number.isFinite(s.unexplainedRate) ? Math.round(s.unexplainedRate * 100) / 100 : 0;
  const e = {
    at: Math.round(at),
    kind,
    id: id3(id),
    tempC: round1(s.measuredC),
    predictedC: round1(s.predictedC),
    excessCPerS: excess,
    secondsToLimit: toLimit,
  };
  return {
    ...e,
    detail: thermalAlertDetail(kind, e.id, e.tempC, e.predictedC, e.excessCPerS, toLimit),
  };
}

const num = (v: unknown): v is number => typeof v === 'number' && Number.isFinite(v);

/** An event read back from `arm/{id}/alert`; null when the payload is not one. */
export function parseThermalAlert(payload: Uint8Array | string): ThermalAlert | null {
  const text = typeof payload === 'string' ? payload : new TextDecoder().decode(payload);
  let v: Partial<ThermalAlert>;
  try {
    v = JSON.parse(text) as Partial<ThermalAlert>;
  } catch {
    return null;
  }
  if (typeof v !== 'object' || v === null) return null;
  if (!(THERMAL_ALERT_KINDS as readonly string[]).includes(v.kind as string)) return null;
  if (typeof v.id !== 'string' || !/^\d{3}$/.test(v.id)) return null;
  if (!num(v.at) || !num(v.tempC) || !num(v.predictedC) || !num(v.excessCPerS)) return null;
  if (v.secondsToLimit !== null && !num(v.secondsToLimit)) return null;
  return {
    at: v.at,
    kind: v.kind as ThermalAlertKind,
    id: v.id,
    tempC: v.tempC,
    predictedC: v.predictedC,
    excessCPerS: v.excessCPerS,
    secondsToLimit: v.secondsToLimit ?? null,
    detail: typeof v.detail === 'string' ? v.detail.slice(0, 500) : '',
  };
}
