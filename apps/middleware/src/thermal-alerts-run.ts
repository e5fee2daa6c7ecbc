/**
 * Runs `ThermalAlerts` (./thermal-alerts.ts) inside the middleware: each early warning it
 * raises or clears is published on `arm/{id}/alert` (QoS 1, not retained) and stored in the
 * arm's log at its own time; each arm's models are refitted from the last `fitSpanMs` of its
 * history every `refitMs` (`/history/thermal-model`'s code, read through the history reader).
 */
import type { Frame } from '@armtwin/protocol';
import { thermalAlertTopic, type ThermalAlert } from '@armtwin/thermal';
import { DEFAULT_HISTORY_OPTIONS } from './history/options.ts';
import type { HistoryReader } from './history/reader.ts';
import { thermalModel } from './history/thermal.ts';
import type { LogOnce, Logger } from './log.ts';
import type { SeriesClock } from './points.ts';
import { ThermalAlerts, thermalAlertLine, type ThermalAlertsOptions } from './thermal-alerts.ts';

export interface ThermalAlertsRunDeps {
  reader: HistoryReader;
  /** Stores line-protocol lines (the spool). */
  store: (lines: string[]) => void;
  /** The ingest's series clock (no two points of one series at one time). */
  clock: SeriesClock;
  publish: (topic: string, payload: string) => void;
  now: () => number;
  log: Logger;
  once: LogOnce;
}

export interface ThermalAlertsRun {
  /** The frames of one message on `arm/{arm}/status`, as the ingest decoded them. */
  frames(arm: string, frames: readonly Frame[]): void;
  stop(): void;
}

/** How often the arms due for a fit are looked for, ms (a new arm waits at most this). */
const FIT_CHECK_MS = 5000;

export function startThermalAlerts(
  options: Partial<ThermalAlertsOptions>,
  deps: ThermalAlertsRunDeps,
): ThermalAlertsRun {
  const heat = new ThermalAlerts(options);
  const ctx = { reader: deps.reader, options: DEFAULT_HISTORY_OPTIONS };
  let fitting = false;

  const refit = async () => {
    if (fitting) return;
    fitting = true;
    try {
      for (const arm of heat.dueForFit(deps.now())) {
        const t = deps.now();
        try {
          const answer = await thermalModel(ctx, {
            arm,
            ids: 'all',
            field: 'temp',
            startMs: t - heat.options.fitSpanMs,
            stopMs: t,
          });
          const fitted = heat.setFit(arm, answer, t);
          deps.log.info({ arm, fitted }, 'thermal models fitted from the history');
        } catch (err) {
          heat.fitFailed(arm, t);
          deps.once.warn('thermal-fit', { arm, err: (err as Error).message }, 'thermal fit failed');
        }
      }
    } finally {
      fitting = false;
    }
  };
  const timer = setInterval(() => void refit(), Math.min(FIT_CHECK_MS, heat.options.refitMs));
  timer.unref();

  const raise = (arm: string, e: ThermalAlert) => {
    deps.store([thermalAlertLine(arm, e, deps.clock)]);
    deps.publish(thermalAlertTopic(arm), JSON.stringify(e));
    deps.log.warn({ arm, servo: e.id, kind: e.kind }, e.detail);
  };

  return {
    frames(arm, frames) {
      for (const e of heat.frames(arm, frames, deps.now())) raise(arm, e);
    },
    stop() {
      clearInterval(timer);
    },
  };
}
