/**
 * The history API's limits, declared once. `createHistoryHandler` merges what it is given
 * over `DEFAULT_HISTORY_OPTIONS`; the README quotes these values.
 */
import type { ThermalFitOptions } from '@armtwin/thermal';

export interface HistoryOptions {
  /** Most points per series that `/history/series` and `/history/pose` return. */
  maxPoints: number;
  /** Longest time range any endpoint accepts, ms (31 days). */
  maxSpanMs: number;
  /**
   * `/history/alarms`: most raw rows read per (servo, field) series after the in-Flux
   * reduction (threshold crossings and in-alarm samples only). Beyond it the answer says
   * `truncated: true`.
   */
  maxAlarmRows: number;
  /**
   * `/history/tracking`: most actual samples compared per joint. Denser data is thinned in
   * Flux to the first sample of each window (see README).
   */
  maxTrackingSamples: number;
  /** `/history/tracking`: how far before `start` to look for the command then in force, ms. */
  commandLookbackMs: number;
  /** Most commands read per joint by `/history/tracking`. */
  maxCommands: number;
  /** Most control events `/history/audit` returns (beyond it, `truncated: true`). */
  maxAuditRows: number;
  /** `/history/thermal-model`: the finest grid step, ms (health arrives at 2 Hz). */
  thermalMinStepMs: number;
  /** `/history/thermal-model`: most grid cells; a longer range gets a coarser step. */
  thermalMaxCells: number;
  /** `/history/thermal-model`: the finest angle window, ms (the state stream's 50 Hz). */
  thermalMinAngleMs: number;
  /** `/history/thermal-model`: most angle windows per servo (a longer range: coarser ones). */
  thermalMaxAngleCells: number;
  /** `/history/thermal-model`: the fit's settings (defaults: `DEFAULT_THERMAL_FIT_OPTIONS`). */
  thermalFit: Partial<ThermalFitOptions>;
  /**
   * `/history/thermal-model`: the supply's internal resistance and common wiring, Ω, across
   * which the motion's power is read from the sag (the simulator's; measure yours once).
   */
  thermalSupplyOhms: number;
}

export const DEFAULT_HISTORY_OPTIONS: HistoryOptions = {
  maxPoints: 2000,
  maxSpanMs: 31 * 24 * 3600_000,
  maxAlarmRows: 50_000,
  maxTrackingSamples: 10_000,
  commandLookbackMs: 24 * 3600_000,
  maxCommands: 50_000,
  maxAuditRows: 10_000,
  thermalMinStepMs: 1000,
  thermalMaxCells: 7200,
  thermalMinAngleMs: 20,
  thermalMaxAngleCells: 40_000,
  thermalFit: {},
  thermalSupplyOhms: 0.3,
};

/** §5 of PROTOCOL.md. */
export const THRESHOLDS = {
  tempWarning: 60,
  tempCritical: 75,
  undervoltage: 6.5,
} as const;

/** Longest move a command can ask for (`tttt` ≤ 9999 ms, PROTOCOL.md §1). */
export const MAX_MOVE_MS = 9999;

/** Where the actual samples for tracking are read from: `MAX_MOVE_MS` + 1 s before start. */
export const actualFromMs = (startMs: number): number => startMs - MAX_MOVE_MS - 1000;
