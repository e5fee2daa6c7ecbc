/**
 * The predictive twin's course as the render worker gets it: the pose the page sampled (for the
 * instant `at`) and the predictor's poses a few steps after it (store/TwinPredictor.ts
 * `poseAhead`). The worker draws later than the page samples (a message, its own frame, the
 * draw itself), so it takes the pose of the instant its frame is shown: linear between the two
 * course poses around it, the sampled pose before `at`, the last course pose after the course
 * (never extrapolated further). Each course pose is a prediction that respects the targets,
 * limits and stops, so a pose between two of them does too. Pure: epoch ms in, no clock.
 */

export interface PoseCourseInput {
  /** The instant the sampled pose is for, ms since the Unix epoch. */
  at: number;
  /** Time between the course's poses, ms. */
  stepMs: number;
  /** The poses at `at + stepMs`, `at + 2·stepMs`, …, joint after joint (`k·n + i`). */
  poses: Float64Array;
}

export class PoseCourse {
  private base: Float64Array = new Float64Array(0);
  private course: PoseCourseInput | null = null;

  /** A new sample: its pose and, for a predicted twin, the course after it (else null). */
  set(base: Float64Array, course: PoseCourseInput | null): void {
    this.base = base;
    this.course =
      course && course.stepMs > 0 && base.length > 0 && course.poses.length >= base.length
        ? course
        : null;
  }

  /**
   * How far past the sample's instant the pose at `epochMs` is, ms: along the course, at most
   * its end (0 without a course, or before the sample's instant).
   */
  aheadAt(epochMs: number): number {
    const c = this.course;
    if (!c) return 0;
    const span = Math.floor(c.poses.length / this.base.length) * c.stepMs;
    return Math.min(span, Math.max(0, epochMs - c.at));
  }

  /** The pose at `epochMs` into `out` (sized as the sample); true if any angle changed. */
  poseAt(epochMs: number, out: Float64Array): boolean {
    const base = this.base;
    const c = this.course;
    const n = base.length;
    let a: Float64Array = base;
    let ia = 0;
    let b: Float64Array = base;
    let ib = 0;
    let f = 0;
    if (c) {
      const steps = Math.floor(c.poses.length / n);
      const x = (epochMs - c.at) / c.stepMs;
      if (x >= steps) {
        a = b = c.poses;
        ia = ib = (steps - 1) * n;
      } else if (x > 0) {
        const k = Math.floor(x);
        f = x - k;
        if (k > 0) {
          a = c.poses;
          ia = (k - 1) * n;
        }
        b = c.poses;
        ib = k * n;
      }
    }
    let changed = false;
    for (let i = 0; i < n && i < out.length; i++) {
      const va = a[ia + i]!;
      const vb = b[ib + i]!;
      // A joint without a prediction (NaN) keeps the sampled value.
      const v = Number.isNaN(va) || Number.isNaN(vb) ? base[i]! : va + (vb - va) * f;
      if (v !== out[i] && !(Number.isNaN(v) && Number.isNaN(out[i]!))) {
        out[i] = v;
        changed = true;
      }
    }
    return changed;
  }
}

export interface PoseCourseOptions {
  /** Time between the course's poses, ms (a corner between two is cut by at most v·step/4). */
  stepMs: number;
  /** Poses sent: the course covers steps × stepMs after the sample (then holds). */
  steps: number;
}

export const DEFAULT_POSE_COURSE_OPTIONS: PoseCourseOptions = { stepMs: 8, steps: 16 };

/** What can predict poses ahead (store/TwinPredictor.ts). */
interface AheadSource {
  readonly count: number;
  poseAhead(from: number, stepMs: number, count: number, out: Float64Array): void;
}

/**
 * The course to send with a sample taken for page time `now`: its instant on the epoch clock
 * (`timeOrigin` is the page's `performance.timeOrigin`) and the poses after it (written into
 * `poses` when given: `steps × count` long).
 */
export function courseAfter(
  p: AheadSource,
  now: number,
  timeOrigin: number,
  o: PoseCourseOptions = DEFAULT_POSE_COURSE_OPTIONS,
  poses: Float64Array = new Float64Array(o.steps * p.count),
): PoseCourseInput {
  p.poseAhead(now, o.stepMs, o.steps, poses);
  return { at: timeOrigin + now, stepMs: o.stepMs, poses };
}
