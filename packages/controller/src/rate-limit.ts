/**
 * The command rate limit: a token bucket (`capacity` tokens, refilled at `ratePerS`, each
 * command takes one) and the gate that puts it in front of the controller. Pure: time comes in
 * as an argument (ms), so the driver's clock (real or fake) drives it.
 */
import type { Frame, Group } from '@armtwin/protocol';

export class TokenBucket {
  private tokens: number;
  private last: number;

  constructor(
    readonly ratePerS: number,
    readonly capacity: number,
    now: number,
  ) {
    if (!(ratePerS > 0) || !(capacity >= 1)) throw new RangeError('rate > 0 and capacity ≥ 1');
    this.tokens = capacity;
    this.last = now;
  }

  /** Takes a token at time `now` if there is one. */
  take(now: number): boolean {
    if (now > this.last) {
      this.tokens = Math.min(
        this.capacity,
        this.tokens + ((now - this.last) * this.ratePerS) / 1000,
      );
      this.last = now;
    }
    if (this.tokens < 1) return false;
    this.tokens -= 1;
    return true;
  }
}

/** One input as the reader gives it. */
export type Input = { frame: Frame } | { group: Group };

/** A stop of one servo or of all: never rate-limited (stopping must always be possible). */
export function isStop(it: Input): boolean {
  if ('frame' in it) return it.frame.type === 'stop';
  return it.group.invalid === 0 && it.group.frames.every((f) => f.type === 'stop');
}

/** `#255PDST!`, alone or inside a valid group. */
export function isEmergencyStop(it: Input): boolean {
  if ('frame' in it) return it.frame.type === 'stop' && it.frame.id === 255;
  return it.group.invalid === 0 && it.group.frames.some((f) => f.type === 'stop' && f.id === 255);
}

/** Pings move nothing and measure the link: limiting them would distort the round trip. */
const costs = (it: Input) =>
  'group' in it || (it.frame.type !== 'time' && it.frame.type !== 'ping');

/**
 * Drops commands over the rate (never stops, pings or stamps). `admit` says what to do with
 * one input: `pass`, `refuse` (the first drop of a run: answer it `$ERR:rate limit!`) or `drop`.
 */
export class CommandGate {
  /** Commands dropped by the rate limit. */
  dropped = 0;
  private limiting = false;
  private readonly bucket: TokenBucket;

  constructor(
    readonly ratePerS: number,
    burst: number,
    now: number,
  ) {
    this.bucket = new TokenBucket(ratePerS, burst, now);
  }

  admit(it: Input, now: number): 'pass' | 'refuse' | 'drop' {
    const c = costs(it);
    if (!c || isStop(it) || this.bucket.take(now)) {
      if (c) this.limiting = false;
      return 'pass';
    }
    this.dropped++;
    if (this.limiting) return 'drop';
    this.limiting = true;
    return 'refuse';
  }
}
