/** Health thresholds of the contract (§5), declared once. */
export const TEMP_WARNING_C = 60;
export const TEMP_CRITICAL_C = 75;
export const VOLTAGE_MIN_V = 6.5;

export type HealthLevel = 'normal' | 'warning' | 'critical';

/** < 60 normal; 60–75 warning; > 75 critical. */
export const temperatureLevel = (celsius: number): HealthLevel =>
  celsius > TEMP_CRITICAL_C ? 'critical' : celsius >= TEMP_WARNING_C ? 'warning' : 'normal';

/** ≥ 6.5 V normal; below it critical. */
export const voltageLevel = (volts: number): HealthLevel =>
  volts < VOLTAGE_MIN_V ? 'critical' : 'normal';

const RANK: Record<HealthLevel, number> = { normal: 0, warning: 1, critical: 2 };
export const worstLevel = (a: HealthLevel, b: HealthLevel): HealthLevel => (RANK[a] >= RANK[b] ? a : b);
