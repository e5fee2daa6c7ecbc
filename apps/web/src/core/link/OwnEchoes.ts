/**
 * The commands this page sent to the arm's control topics, each noted by the page's own
 * predictive twin as it left. The page also reads everyone's commands from the broker, its own
 * among them: that echo is the same command, not a second one, however late it comes back (on
 * a loaded page or network it can come a second later, and a repeated move would restart the
 * twin's course from the wrong place). Each message sent matches one echo, by topic and bytes;
 * one that never comes back (a broker that lets the page write but not read the topic) is
 * forgotten after `ttlMs`. Pure: `now` passed in.
 */
const decoder = new TextDecoder();

interface Sent {
  topic: string;
  payload: string;
  at: number;
}

export class OwnEchoes {
  private sent: Sent[] = [];

  constructor(
    private readonly ttlMs = 10_000,
    private readonly max = 256,
  ) {}

  /** This page published `payload` on `topic` at `now`. */
  note(topic: string, payload: string, now: number): void {
    this.expire(now);
    if (this.sent.length >= this.max) this.sent.shift();
    this.sent.push({ topic, payload, at: now });
  }

  /** Whether a message read from the broker at `now` is one this page sent (each matches once). */
  take(topic: string, payload: string | Uint8Array, now: number): boolean {
    this.expire(now);
    let text: string | undefined;
    for (let i = 0; i < this.sent.length; i++) {
      const s = this.sent[i]!;
      if (s.topic !== topic) continue;
      text ??= typeof payload === 'string' ? payload : decoder.decode(payload);
      if (s.payload !== text) continue;
      this.sent.splice(i, 1);
      return true;
    }
    return false;
  }

  get pending(): number {
    return this.sent.length;
  }

  private expire(now: number): void {
    let n = 0;
    while (n < this.sent.length && now - this.sent[n]!.at > this.ttlMs) n++;
    if (n > 0) this.sent.splice(0, n);
  }
}
