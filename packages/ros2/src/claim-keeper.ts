/**
 * The bridge's side of "one operator at a time" (docs/protocol.md): with `take`, it claims the
 * arm whenever nobody holds it and, while it holds it, beats as the HUD does (`beat` every OPERATOR_BEAT_MS), so its
 * lease lapses within OPERATOR_LEASE_MS if the bridge dies; it never takes an arm someone else
 * holds. Without `take` it only follows the holder record. The controller decides; this only asks.
 * Pure: the clock and the publishing are injected.
 */
import { OPERATOR_BEAT_MS, type Clock, type HolderRecord } from '@armtwin/protocol';

export class ClaimKeeper {
  /** The holder record last seen (undefined: none seen yet). */
  holder: HolderRecord | undefined;
  private beat: unknown;

  constructor(
    private readonly user: string,
    private readonly take: boolean,
    private readonly clock: Clock,
    /** Publishes a claim payload on `arm/{id}/claim/{user}`. */
    private readonly claim: (payload: 'take' | 'beat' | 'release') => void,
  ) {}

  /** Whether the bridge holds the arm. */
  get holds(): boolean {
    return this.holder?.user === this.user;
  }

  /** A new holder record (retained `arm/{id}/holder`; `user` null: nobody, or the arm is gone). */
  onHolder(record: HolderRecord): void {
    this.holder = record;
    if (this.take && this.holder.user === null) this.claim('take');
    if (this.holds) this.startBeat();
    else this.stopBeat();
  }

  /** Lets go of the arm (if held) and stops beating. */
  release(): void {
    this.stopBeat();
    if (this.holds) this.claim('release');
  }

  private startBeat(): void {
    if (this.beat !== undefined) return;
    const tick = () => {
      this.claim('beat');
      this.beat = this.clock.setTimeout(tick, OPERATOR_BEAT_MS);
    };
    this.beat = this.clock.setTimeout(tick, OPERATOR_BEAT_MS);
  }

  private stopBeat(): void {
    if (this.beat !== undefined) this.clock.clearTimeout(this.beat);
    this.beat = undefined;
  }
}
