/**
 * What the scene runtime (./SceneRuntime.ts) said of its last drawn frame, read-only for the
 * page: the Status panel, the Ghost panel, the debug hook and the bench read it here. Nothing
 * here is written back into the store or the target: the renderer reports, it feeds no domain
 * object. The view's `renderHooks` are called after each report (the bench's frame probe).
 */
import type { FromWorker } from './messages.ts';

/**
 * How far the drawn pose is ahead of the newest state report, ms (0 when not predicting): the
 * store's sample lead and the runtime's own, drawing later along the predicted course.
 */
export function drawnLeadMs(
  store: { readonly predicting: boolean; readonly predictionLeadMs: number },
  reports: Pick<ReadonlySceneReports, 'aheadMs'>,
): number {
  return store.predicting ? store.predictionLeadMs + reports.aheadMs : 0;
}

/** One drawn frame's report, as the runtime posts it. */
export type FrameReport = Extract<FromWorker, { type: 'rendered' }>;

/** What the ghost shows (../Ghost.ts). */
export type GhostShows = FrameReport['ghostShows'];

/** The page's read-only view of the reports. */
export interface ReadonlySceneReports {
  /** Frames drawn at the current size (a frame drawn before the latest resize is not counted). */
  readonly frames: number;
  readonly pixelRatio: number;
  /** A moving frame's cost, ms, where frames run on a budget (software WebGL); else 0. */
  readonly costMs: number;
  /** How far past the page's sample the drawn pose is, along the predicted course, ms. */
  readonly aheadMs: number;
  readonly ghostShows: GhostShows;
  /** The URDF joint whose child link the ghost paints red ('' = none). */
  readonly ghostPainted: string;
  /** The level each servo's link is painted at, null before a robot is drawn. */
  readonly trackingLevels: readonly string[] | null;
  /** The URDF joint values drawn, in servo order ([] before a robot). */
  drawn(which: 'robot' | 'ghost' | 'sibling'): number[];
}

export class SceneReports implements ReadonlySceneReports {
  frames = 0;
  pixelRatio = 1;
  costMs = 0;
  aheadMs = 0;
  ghostShows: GhostShows = 'nothing';
  ghostPainted = '';
  trackingLevels: readonly string[] | null = null;
  private last: FrameReport | null = null;

  drawn(which: 'robot' | 'ghost' | 'sibling'): number[] {
    return this.last ? this.last[which].slice() : [];
  }

  /** Takes a report; a frame drawn before the latest resize (`currentSizeSeq`) was wiped by it. */
  take(r: FrameReport, currentSizeSeq: number): void {
    if (r.sizeSeq === currentSizeSeq) this.frames = r.frames;
    this.pixelRatio = r.pixelRatio;
    this.costMs = r.costMs;
    this.aheadMs = r.aheadMs;
    this.ghostShows = r.ghostShows;
    this.ghostPainted = r.ghostPainted;
    this.trackingLevels = r.trackingLevels;
    this.last = r;
  }

  /** Forgets the frames (a fresh runtime draws from 0). */
  reset(): void {
    this.frames = 0;
    this.aheadMs = 0;
    this.last = null;
  }
}
