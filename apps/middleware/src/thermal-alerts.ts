/**
 * The middleware's thermal watch: the same `ThermalWatch` the HUD runs (@armtwin/protocol),
 * over every arm's status stream, so an early warning is raised, published and stored whether
 * or not a page is open. One watch per (arm, servo); each arm's models are refitted from its
 * own history now and then (`dueForFit` says which; index.ts asks `/history/thermal-model`'s
 * code and hands the answer to `setFit`). Until a fit, a servo has the generic model, as in the
 * HUD. Pure: times are arguments, nothing is published or written here.
 */
import type { ThermalModelAnswer } from '@armtwin/api';
import { createReader, isValidArmId, US_PER_DEG, type Frame, type Reader } from '@armtwin/protocol';
import {
  DEFAULT_THERMAL_PARAMS,
  thermalAlert,
  THERMAL_ALERT_BY,
  ThermalWatch,
  type ThermalAlert,
  type ThermalWatchOptions,
} from '@armtwin/thermal';
import { auditLine, auditSeries, type SeriesClock } from './points.ts';

export interface ThermalAlertsOptions {
  /** Each arm's models are refitted from its history this often, ms (and at once when new). */
  refitMs: number;
  /** The history a fit reads, ms back from now. */
  fitSpanMs: number;
  /** Most arms watched; beyond it a new arm is not watched (memory stays bounded). */
  maxArms: number;
  /** The watch's settings (default: `DEFAULT_THERMAL_WATCH_OPTIONS`, as in the HUD). */
  watch: Partial<ThermalWatchOptions>;
}

export const DEFAULT_THERMAL_ALERTS_OPTIONS: ThermalAlertsOptions = {
  refitMs: 5 * 60_000,
  fitSpanMs: 15 * 60_000,
  maxArms: 256,
  watch: {},
};

const STATUS_TOPIC = /^arm\/([^/]+)\/status$/;
/** Most servos watched per arm (ids are 0–254). */
const MAX_SERVOS = 255;

/** One arm: its reader and a watch per servo id. */
class ArmHeat {
  readonly watches = new Map<number, ThermalWatch>();
  readonly reader: Reader;
  fittedAt = -Infinity;
  private arrival = 0;
  private out: ThermalAlert[] = [];

  constructor(private readonly watch: Partial<ThermalWatchOptions>) {
    this.reader = createReader({
      onFrame: (f) => this.frame(f),
      onGroup: (g) => {
        for (const f of g.frames) this.frame({ ...f, time: f.time ?? g.time });
      },
    });
  }

  feed(payload: Uint8Array, arrival: number): ThermalAlert[] {
    this.arrival = arrival;
    this.out = [];
    this.reader.clearStamp();
    this.reader.feed(payload);
    return this.out;
  }

  /** Frames another reader decoded from one message (a group's frames carry its stamp). */
  frames(frames: readonly Frame[], arrival: number): ThermalAlert[] {
    this.arrival = arrival;
    this.out = [];
    for (const f of frames) this.frame(f);
    return this.out;
  }

  private servo(id: number): ThermalWatch | undefined {
    let w = this.watches.get(id);
    if (!w && this.watches.size < MAX_SERVOS) {
      w = new ThermalWatch([DEFAULT_THERMAL_PARAMS], this.watch);
      this.watches.set(id, w);
    }
    return w;
  }

  private frame(f: Frame): void {
    if (f.type === 'position') this.servo(f.id)?.position(0, f.pwm / US_PER_DEG);
    else if (f.type === 'angle') this.servo(f.id)?.position(0, f.deg);
    else if (f.type === 'health') {
      const w = this.servo(f.id);
      const t = f.time ?? this.arrival;
      const e = w?.health(0, t, f.temp);
      if (w && e)
        this.out.push(
          thermalAlert(
            e === 'raised' ? 'thermal-warning' : 'thermal-cleared',
            f.id,
            t,
            w.state(0)!,
          ),
        );
    }
  }
}

export class ThermalAlerts {
  readonly options: ThermalAlertsOptions;
  private readonly arms = new Map<string, ArmHeat>();

  constructor(options: Partial<ThermalAlertsOptions> = {}) {
    this.options = { ...DEFAULT_THERMAL_ALERTS_OPTIONS, ...options };
  }

  /** A message as the middleware received it: the early warnings it raised or cleared. */
  handle(topic: string, payload: Uint8Array, arrival: number): ThermalAlert[] {
    const m = STATUS_TOPIC.exec(topic);
    if (!m || !isValidArmId(m[1]!)) return [];
    return this.arm(m[1]!)?.feed(payload, arrival) ?? [];
  }

  /**
   * The frames of one message on `arm/{armId}/status` as the ingest decoded them (one parse of
   * each payload in the middleware, not two): the same answer as `handle` of that message.
   */
  frames(armId: string, frames: readonly Frame[], arrival: number): ThermalAlert[] {
    return this.arm(armId)?.frames(frames, arrival) ?? [];
  }

  private arm(id: string): ArmHeat | undefined {
    let arm = this.arms.get(id);
    if (!arm) {
      if (this.arms.size >= this.options.maxArms) return undefined;
      arm = new ArmHeat(this.options.watch);
      this.arms.set(id, arm);
    }
    return arm;
  }

  /** The arms whose models are due for a (re)fit at `now`, epoch ms. */
  dueForFit(now: number): string[] {
    const due: string[] = [];
    for (const [id, arm] of this.arms) if (now - arm.fittedAt >= this.options.refitMs) due.push(id);
    return due;
  }

  /** A fit from the arm's history: every fitted servo's model from now on. */
  setFit(armId: string, answer: ThermalModelAnswer, now: number): number {
    const arm = this.arms.get(armId);
    if (!arm) return 0;
    arm.fittedAt = now;
    let fitted = 0;
    for (const s of answer.servos) {
      const w = arm.watches.get(Number(s.id));
      if (w && s.fitted) {
        w.setParams(0, s.params);
        fitted++;
      }
    }
    return fitted;
  }

  /** A fit that failed: tried again after `refitMs` like any other. */
  fitFailed(armId: string, now: number): void {
    const arm = this.arms.get(armId);
    if (arm) arm.fittedAt = now;
  }

  /** The watch of one servo (tests, metrics). */
  watchOf(armId: string, id: number): ThermalWatch | undefined {
    return this.arms.get(armId)?.watches.get(id);
  }
}

/** The stored form of an event: an `audit` point of the arm's log at the event's time. */
export function thermalAlertLine(arm: string, e: ThermalAlert, clock: SeriesClock): string {
  const series = auditSeries(arm, e.kind);
  return auditLine(series, THERMAL_ALERT_BY, e.detail, clock.next(series, e.at * 1000));
}
