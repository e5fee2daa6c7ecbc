/**
 * Rehearse, then run (issue 20; docs/protocol.md § Modes): keeps the trajectory of the last
 * plan run in Model mode (the copy's reported angles: the "rehearsal", the predicted run) and of
 * the run on the real arm that follows it (the actual run), and their tracking error per servo
 * (./compareRuns.ts). A plain object outside React: a timer copies each new status report of the
 * store being driven into the trace being recorded; the Plan panel samples `phase` and `errors`.
 */
import type { ArmStore } from '../store/ArmStore.ts';
import { compareRuns, type JointError, type RunTrace } from './compareRuns.ts';

/** What is kept: nothing, a rehearsal (ready to run on the arm), or both runs compared. */
export type RehearsalPhase = 'none' | 'rehearsing' | 'rehearsed' | 'running' | 'compared';

export interface RunRecorderOptions {
  /** How often the store is looked at for a new status report, ms. */
  pollMs: number;
  /** At most this many samples per trace (a long run keeps its first ones). */
  maxSamples: number;
}

export const DEFAULT_RUN_RECORDER_OPTIONS: RunRecorderOptions = { pollMs: 10, maxSamples: 20_000 };

export class RunRecorder {
  phase: RehearsalPhase = 'none';
  rehearsal: RunTrace | null = null;
  actual: RunTrace | null = null;
  errors: JointError[] | null = null;
  /** The Plan panel's waypoints' version the rehearsal ran (changed since: rehearse again). */
  waypointsVersion = -1;
  /** Bumped when a trace is kept or compared (the panel re-reads then). */
  version = 0;
  private timer: ReturnType<typeof setInterval> | undefined;
  private recording: {
    trace: RunTrace;
    store: ArmStore;
    t0: number;
    seen: number;
    /** The run's first `$TIM`, NaN until one came. */
    stamp0: number;
  } | null = null;
  private readonly opts: RunRecorderOptions;

  constructor(opts: Partial<RunRecorderOptions> = {}) {
    this.opts = { ...DEFAULT_RUN_RECORDER_OPTIONS, ...opts };
  }

  /** A plan starts on the copy (`rehearsal`) or on the arm after a rehearsal (`actual`). */
  begin(kind: 'rehearsal' | 'actual', store: ArmStore, t0: number, waypointsVersion = -1): void {
    this.stopTimer();
    const trace: RunTrace = { t: [], angles: [] };
    if (kind === 'rehearsal') {
      this.waypointsVersion = waypointsVersion;
      this.rehearsal = trace;
      this.actual = null;
      this.errors = null;
      this.phase = 'rehearsing';
    } else {
      this.actual = trace;
      this.errors = null;
      this.phase = 'running';
    }
    this.recording = { trace, store, t0, seen: NaN, stamp0: NaN };
    this.sample();
    this.timer = setInterval(() => this.sample(), this.opts.pollMs);
    this.version++;
  }

  /** The run ended: `done` keeps it (a rehearsal becomes runnable; an actual run is compared). */
  end(done: boolean): void {
    const rec = this.recording;
    if (!rec) return;
    this.sample();
    this.stopTimer();
    this.recording = null;
    if (this.phase === 'rehearsing') {
      this.phase = done ? 'rehearsed' : 'none';
      if (!done) this.rehearsal = null;
    } else if (this.phase === 'running' && this.rehearsal) {
      this.errors = compareRuns(this.rehearsal, rec.trace, rec.store.servoCount);
      this.phase = 'compared';
    }
    this.version++;
  }

  /** Forgets both runs (another arm, new waypoints). */
  clear(): void {
    this.stopTimer();
    this.recording = null;
    this.rehearsal = this.actual = null;
    this.errors = null;
    this.phase = 'none';
    this.version++;
  }

  private stopTimer(): void {
    clearInterval(this.timer);
    this.timer = undefined;
  }

  /**
   * A new status report of the driven store → one sample, timed from the run's start: by the
   * arm's own `$TIM` when its reports carry one (the broker's and the page's delays are not the
   * arm's motion), from the first sample of the run; by arrival (from the click) otherwise.
   */
  private sample(): void {
    const rec = this.recording;
    if (!rec) return;
    const at = rec.store.lastStateAt;
    if (!Number.isFinite(at) || at === rec.seen) return;
    rec.seen = at;
    if (rec.trace.t.length >= this.opts.maxSamples) return;
    const stamp = rec.store.lastStateStamp;
    if (Number.isFinite(stamp) && !Number.isFinite(rec.stamp0)) rec.stamp0 = stamp;
    const t = Number.isFinite(rec.stamp0) ? stamp - rec.stamp0 : at - rec.t0;
    rec.trace.t.push(Math.max(0, t));
    rec.trace.angles.push(Float64Array.from(rec.store.angle));
  }
}
