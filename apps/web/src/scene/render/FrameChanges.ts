/**
 * What the page's state says that the render worker has not been sent yet (./SceneClient.ts):
 * the store's drawn angles (with the predicted course after them), arm profile, commanded pulses
 * and tracking paint, the target, the plan preview and the replay sibling's pose, each copied
 * into the frame's `FrameInput` only when it differs from what was last sent (everything with
 * `full`). Copies, never the page's live arrays: a posted message must not change afterwards.
 */
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { GhostSource } from '../sceneHooks.ts';
import type { SiblingSource } from '../ReplaySibling.ts';
import type { FrameInput, TargetState } from './messages.ts';
import { sameValues, targetDiffers } from './frameDiff.ts';
import { snapshotTarget } from './snapshots.ts';
import { courseAfter } from './PoseCourse.ts';

export class FrameChanges {
  private lastArm: unknown = null;
  private lastCommanded = new Float64Array(0);
  private lastTarget: TargetState | null = null;
  private readonly planBuf = new Float64Array(64);
  private lastPlan: Float64Array | null = null;
  private siblingShown = false;
  private lastTracking = '';

  constructor(
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
    private readonly replay: SiblingSource | null,
  ) {}

  /**
   * Samples the store for `now` (only while `running`) and fills `m` with what changed since
   * the last call (all of it with `full`); true when anything was filled in.
   */
  collect(
    m: FrameInput,
    now: number,
    full: boolean,
    running: boolean,
    ghostSource: GhostSource | null,
  ): boolean {
    let any = false;
    const s = this.store;
    if (running && s.sample(now)) {
      m.rendered = Float64Array.from(s.rendered);
      // The predicted course after the sample: the worker poses the arm for its own frame.
      if (s.opts.twinMode === 'predict')
        m.course = courseAfter(
          s.predictor,
          now + s.predictor.displayLeadMs,
          performance.timeOrigin,
        );
      any = true;
    } else if (full) {
      m.rendered = Float64Array.from(s.rendered);
      any = true;
    }
    if (full || s.opts.arm !== this.lastArm) {
      this.lastArm = s.opts.arm;
      m.arm = s.opts.arm;
      any = true;
    }
    if (full || !sameValues(s.commandedPwm, this.lastCommanded)) {
      this.lastCommanded = Float64Array.from(s.commandedPwm);
      m.commandedPwm = this.lastCommanded;
      any = true;
    }
    if (full || targetDiffers(this.target, this.lastTarget)) {
      this.lastTarget = snapshotTarget(this.target);
      m.target = this.lastTarget;
      any = true;
    }
    const plan = ghostSource?.sample(now, this.planBuf) ? this.planBuf : null;
    if (plan ? !this.lastPlan || !sameValues(plan, this.lastPlan) : this.lastPlan !== null) {
      this.lastPlan = plan ? Float64Array.from(plan) : null;
      m.plan = this.lastPlan;
      any = true;
    }
    if (this.replay) {
      const changed = this.replay.update(now);
      const shown = this.replay.active && this.replay.record !== null;
      if (shown !== this.siblingShown || (shown && changed)) {
        this.siblingShown = shown;
        m.sibling = shown ? Float64Array.from(this.replay.angles) : null;
        any = true;
      }
    }
    const t = s.tracking;
    const trackingKey = t ? `${t.active ? 1 : 0}:${t.version}` : '';
    if (t && (full || trackingKey !== this.lastTracking)) {
      this.lastTracking = trackingKey;
      m.tracking = {
        active: t.active,
        version: t.version,
        colours: Int32Array.from(t.colours),
        levels: t.levels.slice(),
      };
      any = true;
    }
    return any;
  }
}
