/**
 * When the 3D view's loop draws, and at what resolution, for the scene runtime
 * (./render/SceneRuntime.ts), in the render worker or on the main thread: a frame when something moved
 * (or while warming up), the resolution lowered while such frames are slow (ResolutionGovernor),
 * and one full-resolution frame once things have rested a moment, so a lowered resolution only
 * ever shows while things move.
 *
 * A budget (`budget` < 1) caps the share of the wall clock the view's frames may keep the
 * renderer busy. Software WebGL (SwiftShader, llvmpipe) draws every pixel on the CPU, in the
 * browser's GPU process, and a worker's loop asks for frames as fast as they come: unbudgeted,
 * a moving arm keeps a core busy and everything else on the machine (the stop's input and
 * socket, MQTT, the broker) queues for the other. A frame's cost is read from the loop itself:
 * an OffscreenCanvas's next animation frame comes only once the frame drawn is done, so the
 * time from a draw to the next tick is what it cost (a display frame at least, in whole display
 * frames). After a frame that cost c ms the next is drawn no sooner than c / budget ms later;
 * the governor lowers the resolution while c is over `slowMs` (three 60 Hz frames) and raises it
 * while under `fastMs` (one): two frames hold it.
 */
import { ResolutionGovernor } from './ResolutionGovernor.ts';

export interface FramePacerOptions {
  /** Frames drawn back to back after creation, so the resolution fits the machine at once. */
  warmupFrames: number;
  /** Idle time after which one full-resolution frame is drawn, ms. */
  refineAfterMs: number;
  /** Share of the wall clock frames may take, 0–1; 1: a frame whenever something moved. */
  budget: number;
  /**
   * With a budget: a frame's cost over which the resolution drops, and under which it climbs
   * again, ms (without one, the interval between back-to-back frames is the cost, judged by the
   * governor's own thresholds).
   */
  slowMs: number;
  fastMs: number;
}

export const DEFAULT_FRAME_PACER_OPTIONS: FramePacerOptions = {
  warmupFrames: 0,
  refineAfterMs: 300,
  budget: 1,
  slowMs: 40,
  fastMs: 18,
};

/**
 * Software WebGL in the render worker: frames keep the renderer busy half the time at most
 * (12–20 frames a second on a 2-core machine with SwiftShader), the rest of that core is left
 * to the page, the browser and the machine's other work.
 */
export const SOFTWARE_PACING = { budget: 0.5 } satisfies Partial<FramePacerOptions>;

/** How much of each new frame's cost the running estimate takes. */
const COST_SMOOTHING = 0.3;
/**
 * A draw-to-tick time this long is a pause (a hidden tab, a stalled machine), not a frame's
 * cost: not learnt. Below it, a cost counts at most `MAX_COST_MS`, so one slow frame does not
 * hold the next ones back for long.
 */
const PAUSE_MS = 1000;
const MAX_COST_MS = 250;

/** What the pacer sets on the renderer. */
export interface PixelRatioTarget {
  getPixelRatio(): number;
  setPixelRatio(ratio: number): void;
}

export class FramePacer {
  readonly opts: FramePacerOptions;
  readonly governor: ResolutionGovernor;
  private warmupFrames: number;
  /** When the previous step drew (NaN if it did not): frame cost while moving. */
  private lastRenderAt = NaN;
  /** Whether the idle frame at full resolution has been drawn since the last motion. */
  private refined = true;
  private lastMovedAt = 0;
  /** Something moved and its frame waits for the budget. */
  private pending = false;
  /** With a budget: a moving frame's cost, ms, smoothed (0 before the first). */
  costMs = 0;
  /** With a budget: the last frame drawn, whose cost the next tick tells. */
  private costOf: { at: number; moving: boolean } | null = null;
  /** No frame before this instant (the budget). */
  private nextAt = -Infinity;

  constructor(
    private readonly renderer: PixelRatioTarget,
    maxRatio: number,
    opts: Partial<FramePacerOptions> = {},
  ) {
    this.opts = { ...DEFAULT_FRAME_PACER_OPTIONS, ...opts };
    this.warmupFrames = this.opts.warmupFrames;
    this.governor = new ResolutionGovernor(
      this.opts.budget < 1
        ? { maxRatio, slowMs: this.opts.slowMs, fastMs: this.opts.fastMs }
        : { maxRatio },
    );
    renderer.setPixelRatio(this.governor.ratio);
  }

  /**
   * One tick of the loop at `now`: calls `draw(now)` when `moved` (or while warming up), at the
   * governor's resolution, else the full-resolution frame once idle long enough.
   */
  step(now: number, moved: boolean, draw: (now: number) => void): void {
    this.learnCost(now);
    if (this.warmupFrames > 0) {
      this.warmupFrames--;
      moved = true;
    }
    if (moved) {
      this.pending = true;
      this.lastMovedAt = now;
    }
    if (this.pending) {
      if (now < this.nextAt) return;
      this.pending = false;
      // Budgeted, the cost came in learnCost; else the interval between frames is the cost.
      if (this.opts.budget >= 1) this.governor.frame(now - this.lastRenderAt);
      if (this.renderer.getPixelRatio() !== this.governor.ratio)
        this.renderer.setPixelRatio(this.governor.ratio);
      this.drawAt(now, draw, true);
      this.lastRenderAt = now;
      this.refined = false;
    } else {
      this.lastRenderAt = NaN;
      this.refineWhenIdle(now, draw);
    }
  }

  /** Budgeted: the tick after a draw tells its cost, and when the next frame may come. */
  private learnCost(now: number): void {
    const c = this.costOf;
    if (!c) return;
    this.costOf = null;
    const elapsed = now - c.at;
    if (!(elapsed < PAUSE_MS)) {
      this.nextAt = now;
      return;
    }
    const cost = Math.min(elapsed, MAX_COST_MS);
    if (c.moving) {
      this.costMs = this.costMs > 0 ? this.costMs + COST_SMOOTHING * (cost - this.costMs) : cost;
      this.governor.frame(cost);
    }
    // rAF ticks come a display frame apart: one within a millisecond of the limit is taken.
    this.nextAt = c.at + (c.moving ? this.costMs : cost) / this.opts.budget - 1;
  }

  private drawAt(now: number, draw: (now: number) => void, moving: boolean): void {
    draw(now);
    if (this.opts.budget < 1) {
      this.costOf = { at: now, moving };
      this.nextAt = Infinity; // until the next tick says what this frame cost
    }
  }

  private refineWhenIdle(now: number, draw: (now: number) => void): void {
    const full = this.governor.opts.maxRatio;
    if (this.refined || now - this.lastMovedAt < this.opts.refineAfterMs || now < this.nextAt)
      return;
    this.refined = true;
    if (this.governor.ratio >= full) return;
    this.renderer.setPixelRatio(full);
    // The full-resolution frame's cost would skew the moving frames' estimate: not learnt.
    this.drawAt(now, draw, false);
  }
}
