/**
 * A token bucket: `capacity` tokens, refilled at `ratePerS`; each command takes one. Pure:
 * time comes in as an argument (ms), so the controller's clock (real or fake) drives it.
 */
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
