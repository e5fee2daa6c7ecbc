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
export const worstLevel = (a: HealthLevel, b: HealthLevel): HealthLevel =>
  RANK[a] >= RANK[b] ? a : b;

/** Latest temperature (°C) and supply (mV) per servo id. */
export type ServoHealth = Readonly<Record<number, { temp: number; mv: number }>>;

/**
 * The worst level over the servos' latest reports ('unknown' before any) and the words for
 * it ("servo 002: 78 °C; servo 003: 6.10 V", empty when all are normal). One home for these
 * words: the controller's summary (./summary.ts) and the HUD's selected arm use them.
 */
export function healthSummary(health: ServoHealth): {
  level: HealthLevel | 'unknown';
  alarm: string;
} {
  let level: HealthLevel | 'unknown' = 'unknown';
  const words: string[] = [];
  for (const [key, h] of Object.entries(health)) {
    const parts: string[] = [];
    let servo: HealthLevel | 'unknown' = 'unknown';
    if (Number.isFinite(h.temp)) {
      const t = temperatureLevel(h.temp);
      servo = t;
      if (t !== 'normal') parts.push(`${Math.round(h.temp)} °C`);
    }
    if (Number.isFinite(h.mv)) {
      const v = voltageLevel(h.mv / 1000);
      servo = servo === 'unknown' ? v : worstLevel(servo, v);
      if (v !== 'normal') parts.push(`${(h.mv / 1000).toFixed(2)} V`);
    }
    if (servo === 'unknown') continue;
    level = level === 'unknown' ? servo : worstLevel(level, servo);
    if (parts.length > 0) words.push(`servo ${key.padStart(3, '0')}: ${parts.join(', ')}`);
  }
  return { level, alarm: words.join('; ') };
}
