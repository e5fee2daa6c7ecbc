/**
 * The ghost's plan preview: the ghost runs along `plan.samples` again and again (a pause at the
 * end), drawn by the 3D view's one frame loop (`sample` fills the store's degrees; no allocation).
 */
import { samplePlan, type Plan } from '@armtwin/motion';
import { angleFromPwm } from '@armtwin/protocol';
import type { GhostSource } from '../store/viewSources.ts';

/** The ghost holds the end pose this long before the preview starts over, ms. */
export const PREVIEW_HOLD_MS = 800;

export class PlanPreview implements GhostSource {
  plan: Plan | null = null;
  private startedAt = 0;
  private polarity: number[] = [];
  private readonly scratch: number[] = [];

  /** Starts previewing `plan`; `polarity` is the store arm's, servo by servo. */
  show(plan: Plan, polarity: readonly number[], now: number): void {
    this.plan = plan;
    this.polarity = [...polarity];
    this.startedAt = now;
  }

  clear(): void {
    this.plan = null;
  }

  /** Plan time shown at `now`, ms (NaN when no plan). */
  timeAt(now: number): number {
    const p = this.plan;
    if (!p) return NaN;
    return Math.min(p.durationMs, (now - this.startedAt) % (p.durationMs + PREVIEW_HOLD_MS));
  }

  sample(now: number, out: Float64Array): boolean {
    const p = this.plan;
    if (!p) return false;
    const pwm = samplePlan(p, this.timeAt(now), this.scratch);
    for (let i = 0; i < out.length; i++) {
      const v = pwm[i];
      out[i] = v === undefined ? NaN : angleFromPwm(v, this.polarity[i] === -1 ? -1 : 1);
    }
    return true;
  }
}
