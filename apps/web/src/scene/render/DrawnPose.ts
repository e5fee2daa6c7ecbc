/**
 * Poses the live arm's drawn angles (`SceneFrame.rendered`, ./SceneFrame.ts) for each frame the
 * runtime draws: from the page's last sample and the predicted course after it (./PoseCourse.ts),
 * for the instant the frame will be shown — the tick's time plus the tick-to-drawn time it
 * learns from the frames drawn.
 */
import type { FrameInput } from './messages.ts';
import { PoseCourse } from './PoseCourse.ts';
import type { SceneFrame } from './SceneFrame.ts';

export class DrawnPose {
  /** The page's sample and the predicted course after it. */
  private readonly course = new PoseCourse();
  /** Whether a new sample came since the last `poseAt`. */
  private sampled = false;
  /** From a tick's start to its frame drawn, ms (learnt; the pose is taken for then). */
  drawLeadMs = 0;
  /** The tick (epoch ms) the drawn angles were last posed in. */
  private posedAt = NaN;
  /** How far along the course past the page's sample the drawn angles are, ms. */
  aheadMs = 0;

  constructor(private readonly frame: SceneFrame) {}

  /** Takes `m`'s sample and course, if it carries one. */
  take(m: FrameInput): void {
    if (!m.rendered) return;
    this.course.set(m.rendered, m.course ?? null);
    if (this.frame.rendered.length !== m.rendered.length)
      this.frame.rendered = new Float64Array(m.rendered.length).fill(NaN);
    this.sampled = true;
  }

  /**
   * Poses the drawn angles for the frame of the tick at `epochMs` (shown `drawLeadMs` later);
   * whether they changed since the last call.
   */
  poseAt(epochMs = NaN): boolean {
    this.posedAt = epochMs;
    const moved = this.course.poseAt(epochMs + this.drawLeadMs, this.frame.rendered);
    this.aheadMs = Number.isFinite(epochMs) ? this.course.aheadAt(epochMs + this.drawLeadMs) : 0;
    const sampled = this.sampled;
    this.sampled = false;
    return moved || sampled;
  }

  /** The tick's frame was drawn at `epochMs`: learns the lead (a moving average, bounded). */
  drawn(epochMs: number): void {
    const lag = epochMs - this.posedAt;
    if (lag >= 0 && lag <= 100) this.drawLeadMs += 0.1 * (lag - this.drawLeadMs);
  }
}
