/**
 * What the bus gateway reports from its reads (pure): SYNC READ results → the contract's
 * frames, the last readings by servo (for `PRAD`/`PRTV` and the speeds of timed moves), servo
 * error flags as `$ERR` when they change, and which servos have stopped answering (`lost`).
 */
import {
  encodeAngle,
  encodeControllerError,
  encodeGroup,
  encodeHealth,
  MV_MAX,
} from '@armtwin/protocol';
import { degreesPerTick, type BusResult } from '@armtwin/servo-bus';
import type { BusGoal } from './bus-servos.ts';

/** Reads in a row a servo must miss, at least, before it counts as gone. */
export const MISSES_TO_LOSE = 3;

/**
 * A servo that has answered none of the reads asked of it for this long (from the first it
 * missed) counts as gone, ms (docs/arm-side.md). Time, not a count: on a busy machine a
 * scheduling stall makes several reads in a row time out, and a servo must not be lost (then
 * set up again, holding where it is) for that.
 */
export const LOST_AFTER_MS = 1000;

type Positions = Extract<BusResult, { kind: 'positions' }>;
type Health = Extract<BusResult, { kind: 'health' }>;

const id3 = (id: number) => String(id).padStart(3, '0');

export class BusReports {
  /** Last position read, servo degrees, by id. */
  readonly positions = new Map<number, number>();
  /** Last health read, by id. */
  readonly health = new Map<number, { temp: number; mv: number }>();
  private readonly problems = new Map<number, string>();
  /** Servos missing now: since when (the first read missed) and how many reads in a row. */
  private readonly misses = new Map<number, { since: number; count: number }>();
  /** The last goal written to each servo, degrees as commanded. */
  private readonly commanded = new Map<number, number>();

  /** Goals as written, so a servo that reaches one reports it exactly. */
  remember(goals: readonly BusGoal[]): void {
    for (const g of goals) this.commanded.set(g.id, g.degrees);
  }

  /** The last goal written to servo `id`, degrees as commanded (undefined: none yet). */
  goalOf(id: number): number | undefined {
    return this.commanded.get(id);
  }

  /** Forgets the goals (a new calibration reads the same ticks as other angles). */
  forgetGoals(): void {
    this.commanded.clear();
  }

  /**
   * The state group `{#000A+000.00!…}` ('' when nobody answered). A servo resting on the tick
   * of its last goal reports the goal as commanded, so an angle round-trips exactly (+350.00°
   * stays +350.00°, not the 349.98° of tick 3982); anywhere else its tick's angle.
   */
  positionFrames(r: Positions): string {
    const frames: string[] = [];
    for (const s of r.servos) {
      // On the goal's tick: the read angle is within half a tick of the goal's.
      const c = this.commanded.get(s.id);
      const onGoal = c !== undefined && Math.abs(c - s.degrees) < degreesPerTick(s) / 2;
      const degrees = onGoal ? c : s.degrees;
      this.positions.set(s.id, degrees);
      if (Math.abs(degrees) <= 999.99) frames.push(encodeAngle(s.id, degrees));
    }
    return frames.length ? encodeGroup(frames) : '';
  }

  /**
   * The health group `{#000T025V7400!…}` (a 12 V supply is `V12000`, capped at `MV_MAX`), then `$ERR` for each
   * servo whose error flags changed to something; [] when nobody answered.
   */
  healthFrames(r: Health): string[] {
    const frames: string[] = [];
    const errors: string[] = [];
    for (const s of r.servos) {
      const temp = Math.min(999, Math.max(0, Math.round(s.temperatureC)));
      const mv = Math.min(MV_MAX, Math.max(0, Math.round(s.voltageV * 1000)));
      this.health.set(s.id, { temp, mv });
      frames.push(encodeHealth(s.id, temp, mv));
      const problems = s.status.problems.join(' ');
      if (problems !== (this.problems.get(s.id) ?? '')) {
        this.problems.set(s.id, problems);
        if (problems) errors.push(encodeControllerError(`servo ${id3(s.id)} ${problems}`));
      }
    }
    return frames.length ? [encodeGroup(frames), ...errors] : [];
  }

  /**
   * The servos of a read (`asked`, at `now` ms) that are now gone: every read of them missed for
   * `lostAfterMs` since the first miss, and at least `MISSES_TO_LOSE` of them. An answer forgets
   * the misses.
   */
  lost(
    asked: readonly number[],
    missing: readonly number[],
    now: number,
    lostAfterMs = LOST_AFTER_MS,
  ): number[] {
    for (const id of asked) if (!missing.includes(id)) this.misses.delete(id);
    const out: number[] = [];
    for (const id of missing) {
      const m = this.misses.get(id) ?? { since: now, count: 0 };
      m.count++;
      this.misses.set(id, m);
      if (m.count >= MISSES_TO_LOSE && now - m.since >= lostAfterMs) {
        this.misses.delete(id);
        out.push(id);
      }
    }
    return out;
  }
}
