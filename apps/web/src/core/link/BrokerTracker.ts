/**
 * Which broker of the list the link's client is on (docs/protocol.md § Several brokers), for the
 * Status panel, and whether a (re)connect is a move to another broker (a failover, or the move
 * back to the first). Pure: fed the client's `brokers.choice` at every connect.
 */
import { describeBroker, type BrokerChoice } from '@armtwin/link';

export class BrokerTracker {
  /** "Broker 2 of 2: ws://…" while connected with a list of several brokers, '' with one. */
  inUse = '';
  /** Moves to another broker of the list since the first connect. */
  moves = 0;
  private index = -1;

  /**
   * The client connected to `choice` (undefined for a client without a list: nothing changes).
   * True when that is another broker than at the previous connect.
   */
  connectedTo(choice: BrokerChoice | undefined): boolean {
    if (!choice) return false;
    this.inUse = choice.count > 1 ? describeBroker(choice) : '';
    const moved = this.index >= 0 && choice.index !== this.index;
    if (moved) this.moves++;
    this.index = choice.index;
    return moved;
  }
}
