/**
 * A servo's health level (PROTOCOL.md §5, thresholds from @armtwin/protocol) and the words the
 * HUD shows and announces for it. Pure.
 */
import { temperatureLevel, voltageLevel, worstLevel, type HealthLevel } from '@armtwin/protocol';

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
