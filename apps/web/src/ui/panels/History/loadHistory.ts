/**
 * What one load of the History panel fetches, all for the same [start, stop): temperature and
 * voltage of every servo, the tracking-error table, the alarm log — and, per chosen joint, its
 * actual and commanded angle, and the control log (who took, gave and lost control; refused
 * moves; the thermal model's early warnings), and the thermal model fitted from the range with
 * what it predicted there. Each view fails alone (its error is shown in its place).
 */
import type { HistoryApi } from './historyApi.ts';
import type { TimeRange } from './range.ts';
import type {
  AlarmsAnswer,
  AuditAnswer,
  SeriesAnswer,
  ThermalModelAnswer,
  TrackingAnswer,
} from '@armtwin/api';
import type { Loaded } from './loaded.ts';

export interface OverviewViews {
  range: TimeRange;
  temp: Loaded<SeriesAnswer>;
  volt: Loaded<SeriesAnswer>;
  tracking: Loaded<TrackingAnswer>;
  alarms: Loaded<AlarmsAnswer>;
  audit: Loaded<AuditAnswer>;
  /** The thermal model fitted from the range, and what it predicted there (dashed lines). */
  thermal: Loaded<ThermalModelAnswer>;
}

export interface AngleViews {
  range: TimeRange;
  /** Three-digit servo id. */
  id: string;
  actual: Loaded<SeriesAnswer>;
  commanded: Loaded<SeriesAnswer>;
}

const base = (arm: string, r: TimeRange) => ({ arm, start: r.start, stop: r.stop });

export async function loadOverview(
  api: HistoryApi,
  arm: string,
  range: TimeRange,
  signal?: AbortSignal,
): Promise<OverviewViews> {
  const p = base(arm, range);
  const [temp, volt, tracking, alarms, audit, thermal] = await Promise.all([
    api.get<SeriesAnswer>('series', { ...p, field: 'temp' }, signal),
    api.get<SeriesAnswer>('series', { ...p, field: 'volt' }, signal),
    api.get<TrackingAnswer>('tracking', p, signal),
    api.get<AlarmsAnswer>('alarms', p, signal),
    api.get<AuditAnswer>('audit', p, signal),
    api.get<ThermalModelAnswer>('thermal-model', p, signal),
  ]);
  return { range, temp, volt, tracking, alarms, audit, thermal };
}

export async function loadAngles(
  api: HistoryApi,
  arm: string,
  range: TimeRange,
  id: string,
  signal?: AbortSignal,
): Promise<AngleViews> {
  const p = { ...base(arm, range), id };
  const [actual, commanded] = await Promise.all([
    api.get<SeriesAnswer>('series', { ...p, field: 'angle' }, signal),
    api.get<SeriesAnswer>('series', { ...p, field: 'command' }, signal),
  ]);
  return { range, id, actual, commanded };
}

/** Three-digit id of servo index `i` (`2` → `002`). */
export const servoId = (i: number): string => String(i).padStart(3, '0');
