/**
 * The render worker's copies of what the page's Ghost, TargetMarker and ReplaySibling read (the
 * store's drawn angles and commanded pulses, the target, the plan preview, the sibling's pose),
 * refreshed from the page's `FrameInput` messages, so those classes run unchanged in the worker.
 */
import { DEMO_ARM } from '@armtwin/ik';
import { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { GhostStore } from '../Ghost.ts';
import type { SiblingSource } from '../ReplaySibling.ts';
import type { FrameInput } from './messages.ts';
import { PoseCourse } from './PoseCourse.ts';

export class FrameMirror {
  /** What the Ghost reads of the store (and the live arm's drawn angles). */
  readonly store: {
    opts: { arm: GhostStore['opts']['arm'] };
    rendered: Float64Array;
    commandedPwm: Float64Array;
  } = {
    opts: { arm: DEMO_ARM },
    rendered: new Float64Array(0),
    commandedPwm: new Float64Array(0),
  };
  readonly target = new TargetPreview();
  /** The plan preview's pose, null when it shows none. */
  private plan: Float64Array | null = null;
  private readonly sibling = {
    active: false,
    record: null as unknown,
    angles: new Float64Array(0) as Float64Array,
    changed: false,
  };
  /** Whether `store.rendered` changed since the last `takeRendered`. */
  private renderedChanged = false;
  /** The page's sample and the predicted course after it: `store.rendered` is posed from it. */
  private readonly course = new PoseCourse();
  /** From a tick's start to its frame drawn, ms (learnt; the pose is taken for then). */
  drawLeadMs = 0;
  /** The tick (epoch ms) the drawn angles were last posed in. */
  private posedAt = NaN;
  /** How far along the course past the page's sample the drawn angles are, ms. */
  aheadMs = 0;

  /** The replay's sibling as the page last sent it. */
  readonly siblingSource: SiblingSource;

  /** The plan preview as a ghost source (../../robots/sceneHooks.ts's GhostSource). */
  readonly planSource = {
    sample: (_now: number, out: Float64Array): boolean => {
      const p = this.plan;
      if (!p) return false;
      for (let i = 0; i < out.length; i++) out[i] = p[i] ?? NaN;
      return true;
    },
  };

  constructor() {
    const sib = this.sibling;
    this.siblingSource = {
      update: () => {
        const c = sib.changed;
        sib.changed = false;
        return c;
      },
      get active() {
        return sib.active;
      },
      get record() {
        return sib.record;
      },
      get angles() {
        return sib.angles;
      },
    };
  }

  /** Takes the parts of `m` mirrored here. */
  take(m: FrameInput): void {
    if (m.arm) this.store.opts.arm = m.arm;
    if (m.rendered) {
      this.course.set(m.rendered, m.course ?? null);
      if (this.store.rendered.length !== m.rendered.length)
        this.store.rendered = new Float64Array(m.rendered.length).fill(NaN);
      this.renderedChanged = true;
    }
    if (m.commandedPwm) this.store.commandedPwm = m.commandedPwm;
    if (m.target) Object.assign(this.target, m.target);
    if (m.plan !== undefined) this.plan = m.plan;
    if (m.sibling !== undefined) {
      const sib = this.sibling;
      sib.active = m.sibling !== null;
      sib.record = m.sibling === null ? null : true;
      if (m.sibling) sib.angles = m.sibling;
      sib.changed = true;
    }
  }

  /**
   * Poses `store.rendered` for the frame of the tick at `epochMs` (shown `drawLeadMs` later);
   * whether the drawn angles changed since the last call.
   */
  takeRendered(epochMs = NaN): boolean {
    this.posedAt = epochMs;
    const moved = this.course.poseAt(epochMs + this.drawLeadMs, this.store.rendered);
    this.aheadMs = Number.isFinite(epochMs) ? this.course.aheadAt(epochMs + this.drawLeadMs) : 0;
    const c = this.renderedChanged;
    this.renderedChanged = false;
    return moved || c;
  }

  /** The tick's frame was drawn at `epochMs`: learns the lead (a moving average, bounded). */
  drawn(epochMs: number): void {
    const lag = epochMs - this.posedAt;
    if (lag >= 0 && lag <= 100) this.drawLeadMs += 0.1 * (lag - this.drawLeadMs);
  }
}
