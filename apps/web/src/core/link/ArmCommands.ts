/**
 * What the page's controllers may ask of the arm (core/jog, core/plan, core/calibration): its
 * commands, never its connection. ArmLink (./ArmLink.ts) implements it; each controller names the
 * few members it uses (`Pick<ArmCommands, …>`), so a unit test hands in a link or a fake of them.
 */
export interface ArmCommands {
  /** What this page's role may publish. */
  readonly permissions: { readonly command: boolean; readonly stop: boolean };
  /** Whether this page may move the arm now (its role, the mode, and who holds control). */
  readonly mayMove: boolean;
  /** A slider's move, coalesced to one per servo per jog interval. */
  jog(id: number, pwm: number): void;
  /** A hold-to-jog keep-alive: each servo to its pulse in `ms`, one command; false if not sent. */
  holdMoves(moves: ReadonlyArray<readonly [id: number, pwm: number]>, ms: number): boolean;
  /** `#IIIPDST!` for each servo (a hold let go); false if not sent. */
  stopServos(ids: readonly number[]): boolean;
  /** A `{…}` group of timed moves (a plan, a calibration step); false if not sent. */
  sendGroup(frame: string): boolean;
  /** `#255PDST!` to every arm the mode drives, before anything else; false if not sent. */
  emergencyStop(): boolean;
  /** Called first thing by `emergencyStop` (a streamed plan, a hold let go). */
  readonly stopListeners: Set<() => void>;
}
