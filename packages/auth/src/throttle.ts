/**
 * Failed log-ins are throttled (rate-limiter-flexible, in memory): after too many failures from
 * one address, for one user name or in all, that address is locked out for a while, and a
 * locked-out attempt is refused without checking the password — so guessing is slow, and the
 * PBKDF2 work a guess costs is not spent. One throttle serves the embedded broker (MQTT
 * CONNECT) and `armtwin up`'s HTTP Basic (`/api`). Behind a reverse proxy every client has the
 * proxy's address: put the proxy's own limits in front, or run the broker on its own port.
 */
import { RateLimiterMemory } from 'rate-limiter-flexible';
import type { Principal } from './roles.ts';
import type { Users } from './users.ts';

export interface LoginThrottleOptions {
  /** Failures allowed per address and user name in `windowS` before the lockout. */
  perUser: number;
  /** Failures allowed per address, over every user name, in `windowS`. */
  perAddress: number;
  windowS: number;
  /** How long an address is refused once over either budget, s. */
  lockoutS: number;
}

/** A HUD log-in is checked twice (`/api/whoami`, then MQTT CONNECT): 20 checks = 10 tries. */
export const DEFAULT_LOGIN_THROTTLE: LoginThrottleOptions = {
  perUser: 20,
  perAddress: 60,
  windowS: 60,
  lockoutS: 300,
};

export type LoginResult = { ok: true; principal: Principal } | { ok: false; lockedMs: number };

export class LoginThrottle {
  readonly counters = { failed: 0, lockedOut: 0 };
  private readonly byUser: RateLimiterMemory;
  private readonly byAddress: RateLimiterMemory;

  constructor(
    private readonly users: Users,
    o: LoginThrottleOptions = DEFAULT_LOGIN_THROTTLE,
  ) {
    const common = { duration: o.windowS, blockDuration: o.lockoutS };
    this.byUser = new RateLimiterMemory({ ...common, points: o.perUser });
    this.byAddress = new RateLimiterMemory({ ...common, points: o.perAddress });
  }

  /**
   * Checks `name`/`password` from `address` (an IP, or any stable name of the source).
   * `lockedMs` > 0: refused without a check, for about that long still.
   */
  async login(address: string, name: string, password: string | Buffer): Promise<LoginResult> {
    const userKey = `${address}|${name}`;
    const lockedMs = Math.max(
      await this.lockedFor(this.byUser, userKey),
      await this.lockedFor(this.byAddress, address),
    );
    if (lockedMs > 0) {
      this.counters.lockedOut++;
      return { ok: false, lockedMs };
    }
    const principal = this.users.authenticate(name, password);
    if (principal) return { ok: true, principal };
    this.counters.failed++;
    await Promise.all([
      this.byUser.consume(userKey).catch(() => {}),
      this.byAddress.consume(address).catch(() => {}),
    ]);
    return { ok: false, lockedMs: 0 };
  }

  private async lockedFor(limiter: RateLimiterMemory, key: string): Promise<number> {
    const r = await limiter.get(key);
    return r && r.consumedPoints > limiter.points ? Math.max(1, r.msBeforeNext) : 0;
  }
}
