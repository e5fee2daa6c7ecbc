/**
 * What the page's state says that the render worker has not been sent yet (./SceneClient.ts):
 * the store's drawn angles (with the predicted course after them), arm profile, commanded pulses
 * and tracking paint, the target, the plan preview and the replay sibling's pose, each copied
 * into the frame's `FrameInput` when it differs from what the worker was last posted
 * (everything with `full`). The drawn angles go whenever they or the course after them changed:
 * at rest the worker draws the end of the last course it got, so a course posted while the arm
 * was still predicted to move (the first report at the final pose still gave a velocity) is
 * replaced by the resting one even when the sampled angles stayed the same. `collect` only
 * reads; `posted` records what a message carried once it is on its way, so a frame that never
 * left (a part of the page's frame failed before the post) takes nothing with it. Copies, never
 * the page's live arrays: a posted message must not change afterwards.
 */
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { GhostSource } from '../sceneHooks.ts';
import type { SiblingSource } from '../../core/store/viewSources.ts';
import type { FrameInput, TargetState } from './messages.ts';
import { sameValues, targetDiffers } from './frameDiff.ts';
import { snapshotTarget } from './snapshots.ts';
import { courseAfter, DEFAULT_POSE_COURSE_OPTIONS, type PoseCourseInput } from './PoseCourse.ts';

const sameCourse = (a: Float64Array | null, b: Float64Array | null): boolean =>
  a === null || b === null ? a === b : sameValues(a, b);

const trackingKey = (t: { active: boolean; version: number } | null | undefined): string =>
  t ? `${t.active ? 1 : 0}:${t.version}` : '';

export class FrameChanges {
  /** What the worker was last posted (NaN-free comparisons: frameDiff.ts). */
  private lastRendered: Float64Array | null = null;
  /** The course posted with them (null: none, the worker draws the angles as sent). */
  private lastCourse: Float64Array | null = null;
  /** This frame's course, before it is copied into a message. */
  private coursePoses = new Float64Array(0);
  private lastArm: unknown = null;
  private lastCommanded: Float64Array = new Float64Array(0);
  private lastTarget: TargetState | null = null;
  private readonly planBuf = new Float64Array(64);
  private lastPlan: Float64Array | null = null;
  private lastSibling: Float64Array | null = null;
  private lastTracking = '';

  constructor(
    private readonly store: ArmStore,
    private readonly target: TargetPreview,
    private readonly replay: SiblingSource | null,
  ) {}

  /**
   * Samples the store for `now` (only while `running`) and fills `m` with what differs from
   * what the worker was last posted (all of it with `full`); true when anything was filled in.
   * Call `posted(m)` once `m` is on its way.
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
    if (running) s.sample(now);
    // The predicted course after the sample: the worker poses the arm for its own frame.
    const course = running && s.opts.twinMode === 'predict' ? this.courseOf(now) : null;
    if (
      full ||
      !this.lastRendered ||
      !sameValues(s.rendered, this.lastRendered) ||
      !sameCourse(course?.poses ?? null, this.lastCourse)
    ) {
      m.rendered = Float64Array.from(s.rendered);
      if (course) m.course = { ...course, poses: Float64Array.from(course.poses) };
      any = true;
    }
    if (full || s.opts.arm !== this.lastArm) {
      m.arm = s.opts.arm;
      any = true;
    }
    if (full || !sameValues(s.commandedPwm, this.lastCommanded)) {
      m.commandedPwm = Float64Array.from(s.commandedPwm);
      any = true;
    }
    if (full || targetDiffers(this.target, this.lastTarget)) {
      m.target = snapshotTarget(this.target);
      any = true;
    }
    const plan = ghostSource?.sample(now, this.planBuf) ? this.planBuf : null;
    if (plan ? !this.lastPlan || !sameValues(plan, this.lastPlan) : this.lastPlan !== null) {
      m.plan = plan ? Float64Array.from(plan) : null;
      any = true;
    }
    if (this.replay) {
      this.replay.update(now);
      const shown = this.replay.active && this.replay.record !== null;
      const last = this.lastSibling;
      if (shown ? !last || !sameValues(this.replay.angles, last) : last !== null) {
        m.sibling = shown ? Float64Array.from(this.replay.angles) : null;
        any = true;
      }
    }
    const t = s.tracking;
    if (t && (full || trackingKey(t) !== this.lastTracking)) {
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

  /** The store's predicted course after `now`, in a buffer reused from frame to frame. */
  private courseOf(now: number): PoseCourseInput {
    const p = this.store.predictor;
    const o = DEFAULT_POSE_COURSE_OPTIONS;
    if (this.coursePoses.length !== o.steps * p.count)
      this.coursePoses = new Float64Array(o.steps * p.count);
    return courseAfter(p, now + p.displayLeadMs, performance.timeOrigin, o, this.coursePoses);
  }

  /** `m` (filled by `collect`) was posted: the worker has what it carried. */
  posted(m: FrameInput): void {
    if (m.rendered) {
      this.lastRendered = m.rendered;
      this.lastCourse = m.course?.poses ?? null;
    }
    if (m.arm) this.lastArm = m.arm;
    if (m.commandedPwm) this.lastCommanded = m.commandedPwm;
    if (m.target) this.lastTarget = m.target;
    if (m.plan !== undefined) this.lastPlan = m.plan;
    if (m.sibling !== undefined) this.lastSibling = m.sibling;
    if (m.tracking) this.lastTracking = trackingKey(m.tracking);
  }
}
