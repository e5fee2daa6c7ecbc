/** The ArmStore's settings and defaults (./ArmStore.ts), its connection states and counters. */
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';
import type { ThermalWatchOptions } from '@armtwin/thermal';
import type { TwinMode, TwinPredictorOptions } from './TwinPredictor.ts';
import { emptyDropCounters, type DropCounters } from './readerErrors.ts';

export interface ArmStoreOptions {
  /** The arm's profile: servo count, names, polarity. */
  arm: ArmProfile;
  /** The seed's α: > 1 reaches each reported pose sooner, < 1 later (smoother, laggier). */
  interpolationAlpha: number;
  /** Health rows kept for the strip charts (at 2 Hz, 240 = two minutes). */
  historyLength: number;
  /** No state report for longer than this, ms, and the data is stale. */
  staleAfterMs: number;
  /**
   * State reports per second (over the last second) from which each report is drawn as it is,
   * not tweened: reports then come faster than frames, and a tween toward the newest one only
   * lags behind it (by up to a report interval, more when a busy page takes several reports at
   * once). Below it, reports are interpolated (a 5 Hz arm glides).
   */
  drawNewestAboveHz: number;
  /**
   * How the arm is drawn: `predict` (where it is at the display instant, from its reports,
   * their `$TIM` and what was commanded: ./TwinPredictor.ts), `interpolate` (the seed's tween
   * toward each report, drawn as it is above `drawNewestAboveHz`) or `newest` (each report as it is).
   */
  twinMode: TwinMode;
  predictor: Partial<TwinPredictorOptions>;
  /** The thermal early warning's settings (@armtwin/protocol `DEFAULT_THERMAL_WATCH_OPTIONS`). */
  thermal: Partial<ThermalWatchOptions>;
}

export const DEFAULT_ARM_STORE_OPTIONS: ArmStoreOptions = {
  arm: DEMO_ARM,
  interpolationAlpha: 1,
  historyLength: 240,
  staleAfterMs: 1000,
  drawNewestAboveHz: 100,
  twinMode: 'predict',
  predictor: {},
  thermal: {},
};

export type ConnectionState =
  'idle' | 'connecting' | 'connected' | 'reconnecting' | 'offline' | 'error';

export interface StoreCounters extends DropCounters {
  /** MQTT messages on the status topic. */
  messages: number;
  /** Frames decoded (group members included). */
  frames: number;
  /** `$ERR` frames from the controller. */
  controllerErrors: number;
  /** Messages this HUD published on the control topic. */
  published: number;
}

export function emptyStoreCounters(): StoreCounters {
  return { messages: 0, frames: 0, ...emptyDropCounters(), controllerErrors: 0, published: 0 };
}
