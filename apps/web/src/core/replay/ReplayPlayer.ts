/**
 * The replay as a plain object: the loaded pose record, the clock, and the sibling arm's
 * current servo angles in the active robot's terms (`configure`, from its profile). The frame
 * loop calls `update(now)` (no React, no allocation); the panel calls `load`/`play`/`pause`/
 * `seek`/`setSpeed` and samples the position a few times a second. Exposed as `window.__armtwin.replay` (read-only by convention).
 */
import { poseAt, slotsFor, type PoseRecord } from './poseAt.ts';
import { ReplayClock, type ReplaySpeed } from './ReplayClock.ts';

export interface ReplayRecord extends PoseRecord {
  ids: string[];
  /** The selected range, epoch ms: what the scrubber spans. */
  start: number;
  stop: number;
  /** An imported dataset's episode (its own time, not the arm's history), by its name. */
  dataset?: string;
  /**
   * A dataset's `action` (the commanded targets), frame by frame like `angles` (same `ids` and
   * `times`, store degrees at k = 1), shown beside the replayed state.
   */
  action?: PoseRecord['angles'];
}

export class ReplayPlayer {
  readonly clock = new ReplayClock();
  /**
   * The sibling's servo angles now, in the store's degrees of the active robot (NaN = no record
   * for that servo yet). Replaced by `configure` (read it through the player each time).
   */
  angles: Float64Array;
  /** The record's `action` at the instant, as `angles` (all NaN when the record has none). */
  actionAngles: Float64Array;
  record: ReplayRecord | null = null;
  /** Whether the sibling arm is shown. */
  active = false;
  /** Frame index drawn now (−1 before the first frame). */
  frame = -1;
  /** Bumped whenever `angles` is recomputed (for tests and the panel). */
  version = 0;
  /** Each servo's mounting polarity k (§2) in the active robot's store profile. */
  private polarities: readonly number[] = [];
  /** Each servo's id in the active robot's profile, by index. */
  private servoIds: readonly number[] = [];
  private slots: Int16Array = new Int16Array(0);
  private drawnAt = NaN;
  private dirty = false;

  /** As `configure`'s (none until the active robot is known). */
  constructor(polarities: readonly number[] = [], servoIds?: readonly number[]) {
    this.angles = new Float64Array(polarities.length).fill(NaN);
    this.actionAngles = new Float64Array(polarities.length).fill(NaN);
    this.polarities = [...polarities];
    this.servoIds = servoIds ?? polarities.map((_, i) => i);
  }

  /**
   * A new active robot: its servos' mounting polarities k (§2) in the store's profile. The
   * record's `angle` is the pulse's angle at k = 1, so the servo angle the store (and the joint
   * map) counts in is k × that. `servoIds`: each servo's id (default: its index). A record
   * loaded before belonged to the robot before: closed.
   */
  configure(polarities: readonly number[], servoIds?: readonly number[]): void {
    if (this.record) this.close();
    this.polarities = [...polarities];
    this.servoIds = servoIds ?? polarities.map((_, i) => i);
    this.angles = new Float64Array(polarities.length).fill(NaN);
    this.actionAngles = new Float64Array(polarities.length).fill(NaN);
  }

  /** Shows the sibling at the record's start, paused. */
  load(record: ReplayRecord): void {
    this.record = record;
    this.slots = slotsFor(record.ids, this.servoIds);
    this.angles.fill(NaN);
    this.actionAngles.fill(NaN);
    this.clock.load(record.start, record.stop);
    this.active = true;
    this.dirty = true;
  }

  /** Hides the sibling and forgets the record. */
  close(): void {
    this.clock.pause();
    this.record = null;
    this.active = false;
    this.dirty = true;
  }

  play(): void {
    this.clock.play();
  }

  pause(): void {
    this.clock.pause();
  }

  seek(t: number): void {
    this.clock.seek(t);
    this.dirty = true;
  }

  setSpeed(speed: ReplaySpeed): void {
    this.clock.setSpeed(speed);
  }

  /** Frame loop: advances the clock and recomputes the angles; true if they may have changed. */
  update(now: number): boolean {
    const rec = this.record;
    if (!rec) {
      const was = this.dirty;
      this.dirty = false;
      return was;
    }
    const t = this.clock.tick(now);
    if (!this.dirty && t === this.drawnAt) return false;
    this.dirty = false;
    this.drawnAt = t;
    this.frame = poseAt(rec, this.slots, t, this.angles);
    if (rec.action)
      poseAt({ times: rec.times, angles: rec.action }, this.slots, t, this.actionAngles);
    const a = this.angles;
    const c = this.actionAngles;
    for (let i = 0; i < a.length; i++) {
      a[i]! *= this.polarities[i] ?? 1;
      c[i]! *= this.polarities[i] ?? 1;
    }
    this.version++;
    return true;
  }
}
