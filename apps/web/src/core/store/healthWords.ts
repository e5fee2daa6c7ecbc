/**
 * A servo's health level (PROTOCOL.md §5, thresholds from @armtwin/protocol) and the words the
 * HUD shows and announces for it. Pure.
 */
import {
  TEMP_WARNING_C,
  temperatureLevel,
  voltageLevel,
  worstLevel,
  type HealthLevel,
} from '@armtwin/protocol';
import { type ThermalState } from '@armtwin/thermal';

export interface ServoHealth {
  temperatureLevel: HealthLevel | 'unknown';
  voltageLevel: HealthLevel | 'unknown';
  /** The worse of the two. */
  level: HealthLevel | 'unknown';
  /** One sentence for assistive technology and the panel, e.g. "Shoulder: temperature 80 °C, critical — cut the power. Voltage 7.4 V, normal." */
  words: string;
}

const TEMP_WORDS: Record<HealthLevel, string> = {
  normal: 'normal',
  warning: 'warning, hot',
  critical: 'critical, overheating — cut the power',
};
const VOLT_WORDS: Record<HealthLevel, string> = {
  normal: 'normal',
  warning: 'low',
  critical: 'critical, below 6.5 V',
};

export function servoHealth(name: string, celsius: number, millivolts: number): ServoHealth {
  const hasT = Number.isFinite(celsius);
  const hasV = Number.isFinite(millivolts);
  const volts = millivolts / 1000;
  const t = hasT ? temperatureLevel(celsius) : 'unknown';
  const v = hasV ? voltageLevel(volts) : 'unknown';
  const level = t === 'unknown' ? v : v === 'unknown' ? t : worstLevel(t, v);
  const tempText = hasT
    ? `temperature ${Math.round(celsius)} °C, ${TEMP_WORDS[t as HealthLevel]}`
    : 'temperature not reported';
  const voltText = hasV
    ? `voltage ${volts.toFixed(2)} V, ${VOLT_WORDS[v as HealthLevel]}`
    : 'voltage not reported';
  return {
    temperatureLevel: t,
    voltageLevel: v,
    level,
    words: `${name}: ${tempText}; ${voltText}.`,
  };
}

/**
 * The early warning of the thermal model (@armtwin/protocol ThermalWatch) in words, e.g.
 * "Shoulder is heating 2.4 °C/s, 2.2 °C/s more than its motion explains: 60 °C in about 11 s.
 * Look for a jam or a load." '' when there is no warning.
 */
export function thermalWarningWords(name: string, s: ThermalState | undefined): string {
  if (!s?.warning) return '';
  const fix = (x: number) => (Number.isFinite(x) ? x.toFixed(1) : '?');
  const eta =
    s.secondsToLimit <= 0
      ? `already at ${TEMP_WARNING_C} °C`
      : Number.isFinite(s.secondsToLimit)
        ? `${TEMP_WARNING_C} °C in about ${Math.max(1, Math.round(s.secondsToLimit))} s`
        : 'not heating now';
  return (
    `${name} is heating ${fix(s.measuredRate)} °C/s, ${fix(s.unexplainedRate)} °C/s more than ` +
    `its motion explains: ${eta}. Look for a jam or a load.`
  );
}
