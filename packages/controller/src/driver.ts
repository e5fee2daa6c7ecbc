/**
 * What a driver is to the controller core: the thing that has the servos. It feeds the core
 * measured positions and health and carries out the core's goals; it decides nothing (limits,
 * the floor, zones, `$KMS`, the rate limit, the deadman and the e-stop are the core's). Times
 * are the driver's clock, ms, handed to the core with each call.
 *
 * - The simulated servos (`@armtwin/sim`): positions are the servo model's at `t`; a goal starts
 *   a linear segment.
 * - The servo bus (`@armtwin/gateway`, `--bus`): positions are the last SYNC READ; a goal is a
 *   goal position and a speed written to the bus.
 * - An LSC board (`@armtwin/gateway`, `--bus lsc`): firmware with its own servo loop; positions
 *   are what it reports, a goal is a timed move frame written to it, reads and pings are relayed.
 */

import type { Frame } from '@armtwin/protocol';

/** One servo's goal: joint `i` to pulse-equivalent `pwm` (exact µs), arriving in `ms` (0 = as fast as allowed). */
export interface Goal {
  i: number;
  pwm: number;
  ms: number;
  /** The servo angle asked, when the command was a §8 angle move (a driver may pass it on as one). */
  deg?: number;
}

/** A read the driver answers: the encoded frame, or why it cannot. */
export type ReadAnswer = { frame: string } | { refused: string };

export interface ControllerDriver {
  /** '' when goals can be carried out now, else why not (`gateway: serial line down`). */
  unready(): string;
  /** Each joint's position at `t`, exact pulse-equivalent µs by joint index (NaN: unknown). */
  pose(t: number): number[];
  /** Whether any joint is still on its way to its goal at `t`. */
  moving(t: number): boolean;
  /** Starts the goals at `t`, together. */
  move(goals: readonly Goal[], t: number): void;
  /** Stops these joints where they are at `t` (the e-stop and the deadman: every joint). */
  hold(indices: readonly number[], t: number): void;
  /** `#IIIPRAD!` / `#IIIPRTV!` for joint `i`: its position or health frame. */
  read(kind: 'position' | 'health', i: number, t: number): ReadAnswer;
  /**
   * A driver in front of a controller of its own (LSC firmware) that answers reads and pings
   * itself: the checked `PRAD` / `PRTV` / `$PNG` frames of one command are handed here instead of
   * `read` (after its goals), to pass on (`grouped`: they came in a `{…}` group). Returns '' or
   * why they could not be.
   */
  relay?(frames: readonly Frame[], grouped: boolean, t: number): string;
}
