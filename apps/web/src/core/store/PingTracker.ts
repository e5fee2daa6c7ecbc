/**
 * `$PNG` round trips: remembers when each of the last few pings was sent and turns an echo
 * into a round-trip time. Sequence numbers wrap at the protocol's maximum.
 */
import { PING_SEQ_MAX } from '@armtwin/protocol';

const SLOTS = 16;

export class PingTracker {
  private readonly seqs = new Float64Array(SLOTS).fill(NaN);
  private readonly sentAt = new Float64Array(SLOTS);
  private nextSeq: number;
  /** Latest round-trip time, ms (NaN before the first echo). */
  rttMs = NaN;
  /** When the latest echo came, ms. */
  lastEchoAt = NaN;
  sent = 0;
  echoed = 0;

  /** `startSeq`: random by default, so two HUDs on one arm do not take each other's echoes. */
  constructor(startSeq = Math.floor(Math.random() * 1e9)) {
    this.nextSeq = startSeq;
  }

  /** Allocates the next sequence number, records `now` as its send time, and returns it. */
  send(now: number): number {
    const seq = this.nextSeq;
    this.nextSeq = seq >= PING_SEQ_MAX ? 0 : seq + 1;
    this.seqs[seq % SLOTS] = seq;
    this.sentAt[seq % SLOTS] = now;
    this.sent++;
    return seq;
  }

  /** An echo of `seq` arrived at `now`; unknown (or someone else's) sequence numbers are ignored. */
  echo(seq: number, now: number): void {
    const slot = seq % SLOTS;
    if (this.seqs[slot] !== seq) return;
    this.seqs[slot] = NaN;
    this.rttMs = now - this.sentAt[slot]!;
    this.lastEchoAt = now;
    this.echoed++;
  }

  reset(): void {
    this.seqs.fill(NaN);
    this.rttMs = NaN;
    this.lastEchoAt = NaN;
  }
}
