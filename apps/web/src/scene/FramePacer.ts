/**
 * When the 3D view's loop draws, and at what resolution, for the page's Viewer (./Viewer.ts)
 * and the render worker's scene (./render/WorkerScene.ts) alike: a frame when something moved
 * (or while warming up), the resolution lowered while such frames are slow (ResolutionGovernor),
 * and one full-resolution frame once things have rested a moment, so a lowered resolution only
 * ever shows while things move.
 */
import { ResolutionGovernor } from './ResolutionGovernor.ts';

export interface FramePacerOptions {
  /** Frames drawn back to back after creation, so the resolution fits the machine at once. */
  warmupFrames: number;
  /** Idle time after which one full-resolution frame is drawn, ms. */
  refineAfterMs: number;
}

export const DEFAULT_FRAME_PACER_OPTIONS: FramePacerOptions = {
  warmupFrames: 0,
  refineAfterMs: 300,
};

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

  constructor(
    private readonly renderer: PixelRatioTarget,
    maxRatio: number,
    opts: Partial<FramePacerOptions> = {},
  ) {
    this.opts = { ...DEFAULT_FRAME_PACER_OPTIONS, ...opts };
    this.warmupFrames = this.opts.warmupFrames;
    this.governor = new ResolutionGovernor({ maxRatio });
    renderer.setPixelRatio(this.governor.ratio);
  }

  /**
   * One tick of the loop at `now`: calls `draw(now)` when `moved` (or while warming up), at the
   * governor's resolution, else the full-resolution frame once idle long enough.
   */
  step(now: number, moved: boolean, draw: (now: number) => void): void {
    if (this.warmupFrames > 0) {
      this.warmupFrames--;
      moved = true;
    }
    if (moved) {
      this.governor.frame(now - this.lastRenderAt);
      if (this.renderer.getPixelRatio() !== this.governor.ratio)
        this.renderer.setPixelRatio(this.governor.ratio);
      draw(now);
      this.lastRenderAt = now;
      this.lastMovedAt = now;
      this.refined = false;
    } else {
      this.lastRenderAt = NaN;
      this.refineWhenIdle(now, draw);
    }
  }

  private refineWhenIdle(now: number, draw: (now: number) => void): void {
    const full = this.governor.opts.maxRatio;
    if (this.refined || now - this.lastMovedAt < this.opts.refineAfterMs) return;
    this.refined = true;
    if (this.governor.ratio >= full) return;
    this.renderer.setPixelRatio(full);
    draw(now);
  }
}
