/**
 * The controller's side of "one operator at a time" (docs/protocol.md): it keeps who holds the
 * arm, lets only the holder's moves through, and answers everyone else. The simulator and the
 * gateways put it in front of their control input. Identity comes from the topic
 * (`control-claims.ts` of @armtwin/protocol): `arm/{id}/control/{user}` is the user's own control topic.
 *
 * - Nobody holds the arm: every control payload passes, on the plain topic or a user's, as
 *   before there was any holder (the anonymous demo, `mosquitto_pub -t arm/arm1/control`).
 * - Someone holds it: only the holder's payloads pass. Anyone else's stops, reads and pings
 *   pass (the e-stop wins over everything, for everyone who may publish it); their moves are
 *   refused with `$ERR:controlled by <holder>…!` and an audit event, and never reach the arm.
 * - Every change of holder (release, grant, admin take-over, a lapsed lease) stops the arm.
 * - The holder's lease: once a holder repeats `beat`, `leaseMs` without one loses the arm
 *   (the page went idle or away), as the operator lease does (`OperatorWatch` of @armtwin/protocol).
 * - Every emergency stop (`#255PDST!`) that reaches the arm is an audit event `e-stop` with its
 *   sender, and the first move after it that reaches the arm is `e-stop-released` with its
 *   sender: who stopped the arm, and who set it going again.
 *
 * Pure: the clock, the timers and every output are injected.
 */
import {
  createReader,
  EMERGENCY_STOP,
  encodeFrame,
  OPERATOR_LEASE_MS,
  OperatorWatch,
  parseClaim,
  parseUserTopic,
  SERVO_ID_ALL,
  type AuditEvent,
  type AuditKind,
  type Claim,
  type Clock,
  type FrameType,
  type HolderRecord,
  type HolderRole,
} from '@armtwin/protocol';

export interface ControlArbiterIo extends Clock {
  /** Hands a control payload to the arm (what the plain control topic used to do). */
  forward(payload: Uint8Array | string): void;
  /** Says why a payload was refused: a `$ERR` on the arm's status topic. */
  refuse(message: string): void;
  /** Publishes the holder record (retained, `arm/{id}/holder`). */
  holder(record: HolderRecord): void;
  /** Publishes one control event (`arm/{id}/audit`, not retained). */
  audit(event: AuditEvent): void;
}

export interface ControlArbiterOptions {
  /** A holder that has beaten is let go after this long without a `beat`, ms (0 = never). */
  leaseMs: number;
  /** Most users waiting with a request at once; later ones are refused. */
  maxRequests: number;
  /** Least time between two reports (audit and `$ERR`) of one user's refused moves, ms. */
  refusalReportMs: number;
}

export const DEFAULT_CONTROL_ARBITER_OPTIONS: ControlArbiterOptions = {
  leaseMs: OPERATOR_LEASE_MS,
  maxRequests: 8,
  refusalReportMs: 1000,
};

/** Frames a non-holder may still send: they never move the arm, and the stop makes it safer. */
const ANYONE: ReadonlySet<FrameType> = new Set(['stop', 'readPosition', 'readHealth', 'ping']);

/** The plain topic's author in audit events. */
const PLAIN = '';

interface Holder {
  user: string;
  role: HolderRole;
  since: number;
}

export class ControlArbiter {
  readonly counters = { forwarded: 0, refusedCommands: 0, refusedClaims: 0, handOvers: 0 };
  private current: Holder | null = null;
  private requests: string[] = [];
  private readonly lease: OperatorWatch;
  private readonly o: ControlArbiterOptions;
  private readonly lastReport = new Map<string, number>();
  /** An emergency stop reached the arm and nothing has moved it since. */
  private stopped = false;
  /** The sender of the payload being handed to the arm right now ('' = the plain topic). */
  private forwarding = PLAIN;

  constructor(
    readonly armId: string,
    private readonly io: ControlArbiterIo,
    options: Partial<ControlArbiterOptions> = {},
  ) {
    this.o = { ...DEFAULT_CONTROL_ARBITER_OPTIONS, ...options };
    this.lease = new OperatorWatch(
      io,
      () => {
        const who = this.current?.user ?? '';
        this.change(null, who, 'lost', `${who} stopped answering: control lost, arm stopped`);
      },
      this.o.leaseMs,
    );
  }

  /** The filters a controller subscribes to (besides the plain control topic). */
  get filters(): string[] {
    return ['control/+', 'claim/+', 'override/+'].map((k) => `arm/${this.armId}/${k}`);
  }

  get holder(): HolderRecord {
    const h = this.current;
    return h
      ? { user: h.user, role: h.role, since: h.since, requests: [...this.requests] }
      : { user: null, requests: [] };
  }

  /** Publishes the holder record again (at every connect of the controller). */
  announce(): void {
    this.io.holder(this.holder);
  }

  /** Forgets the holder without acting (the controller stops). */
  reset(): void {
    this.lease.reset();
    this.current = null;
    this.requests = [];
  }

  /**
   * A message on one of `filters`, or on the plain control topic: true when it was one of
   * this arbiter's topics.
   */
  fromMessage(topic: string, payload: Uint8Array | string): boolean {
    if (topic === `arm/${this.armId}/control`) {
      this.fromControl(PLAIN, payload);
      return true;
    }
    const t = parseUserTopic(topic);
    if (!t || t.armId !== this.armId || t.kind === 'request') return false;
    if (t.kind === 'control') this.fromControl(t.user, payload);
    else if (t.kind === 'claim') this.fromClaim(t.user, payload);
    else this.fromOverride(t.user, payload);
    return true;
  }

  /** A control payload from `user` ('' = the plain topic, nobody in particular). */
  fromControl(user: string, payload: Uint8Array | string): void {
    const h = this.current;
    const allowed = !h || (user !== PLAIN && h.user === user);
    // The payload is read only when it matters: a non-holder's (its stops pass, its moves do not)
    // or one that may be or follow an emergency stop (the record). A holder's jog goes straight on.
    if (allowed && !this.stopped && !mentionsStop(payload)) {
      this.counters.forwarded++;
      return this.hand(user, payload, null);
    }
    const seen = screen(payload);
    if (allowed || !seen.blocked) {
      this.counters.forwarded++;
      return this.hand(user, payload, seen);
    }
    // The stops in it still stop the arm.
    if (seen.passed.length) this.hand(user, seen.passed.join(''), { ...seen, blocked: false });
    if (this.report(user, h.user, 'to move the arm')) this.io.refuse(`controlled by ${h.user}`);
  }

  /**
   * The sender of the payload the arm is taking in right now, while `forward` runs: the
   * controller names it when it refuses a move itself (a keep-out zone: `record`).
   */
  get author(): string {
    return this.forwarding;
  }

  /** An event the controller itself saw (a move refused by a keep-out zone), published as audit. */
  record(by: string, kind: AuditKind, detail: string): void {
    this.event(by, kind, detail);
  }

  /** An emergency stop, or the first move after one, goes on the record with its sender. */
  private noteStops(user: string, seen: Screened): void {
    const who = user || 'a client on a plain topic';
    if (seen.emergencyStop) {
      this.stopped = true;
      this.event(user, 'e-stop', `${who} pressed the emergency stop`);
    } else if (this.stopped && seen.blocked) {
      this.stopped = false;
      this.event(user, 'e-stop-released', `${who} moved the arm again after the emergency stop`);
    }
  }

  /** Hands a payload to the arm (`seen`: read, for the record of stops; null: nothing to note). */
  private hand(user: string, payload: Uint8Array | string, seen: Screened | null): void {
    if (seen) this.noteStops(user, seen);
    this.forwarding = user;
    try {
      this.io.forward(payload);
    } finally {
      this.forwarding = PLAIN;
    }
  }

  /**
   * Whether `user` ('' = a plain topic) may move the arm now by other means (a motion request
   * that executes): '' if so, else why not (counted and audited as a refused command).
   */
  refusal(user: string, what: string): string {
    const h = this.current;
    if (!h || (user !== PLAIN && h.user === user)) return '';
    this.report(user, h.user, what);
    return `controlled by ${h.user}`;
  }

  /** Counts a refused command; audits it unless this sender's last report is too recent. */
  private report(user: string, holder: string, what: string): boolean {
    this.counters.refusedCommands++;
    const now = this.io.now();
    const key = user || '(plain)';
    if (now - (this.lastReport.get(key) ?? -Infinity) < this.o.refusalReportMs) return false;
    this.lastReport.set(key, now);
    const who = user ? user : 'a client on a plain topic';
    this.event(user, 'refused-command', `${who} tried ${what} ${holder} holds: not sent`);
    return true;
  }

  fromClaim(user: string, payload: Uint8Array | string): void {
    const claim = parseClaim(payload);
    if ('error' in claim) return this.refuseClaim(user, claim.error);
    this.claim(user, claim);
  }

  /** `take` on `arm/{id}/override/{user}`: an administrator takes the arm outright. */
  fromOverride(user: string, payload: Uint8Array | string): void {
    const claim = parseClaim(payload);
    if ('error' in claim || claim.op !== 'take')
      return this.refuseClaim(user, 'override: only take is understood');
    const h = this.current;
    if (h?.user === user) return this.claim(user, { op: 'take' });
    const from = h ? ` from ${h.user}` : '';
    this.change(
      { user, role: 'admin', since: this.io.now() },
      user,
      h ? 'admin-take-over' : 'taken',
      `${user} (admin) took control${from}`,
    );
  }

  private claim(user: string, c: Claim): void {
    const h = this.current;
    const mine = h?.user === user;
    switch (c.op) {
      case 'take':
        if (mine) return this.lease.receive('1');
        if (h) return this.refuseClaim(user, `controlled by ${h.user}: ask for control`);
        return this.change(
          { user, role: 'operator', since: this.io.now() },
          user,
          'taken',
          `${user} took control`,
        );
      case 'beat':
        if (mine) this.lease.receive('1');
        return; // a stale beat from a page that lost the arm: ignored
      case 'ask':
        if (!h) return this.claim(user, { op: 'take' });
        if (mine || this.requests.includes(user)) return;
        if (this.requests.length >= this.o.maxRequests)
          return this.refuseClaim(user, 'too many requests waiting');
        this.requests.push(user);
        this.event(user, 'asked', `${user} asked ${h.user} for control`);
        return this.announce();
      case 'release':
        if (mine) return this.change(null, user, 'released', `${user} released control`);
        if (!this.requests.includes(user)) return;
        this.requests = this.requests.filter((r) => r !== user);
        this.event(user, 'withdrawn', `${user} withdrew the request`);
        return this.announce();
      case 'grant':
      case 'refuse':
        if (!mine)
          return this.refuseClaim(
            user,
            h ? `only ${h.user} may ${c.op} control` : `nobody holds the arm: nothing to ${c.op}`,
          );
        if (!this.requests.includes(c.to))
          return this.refuseClaim(user, `${c.to} has not asked for control`);
        if (c.op === 'grant')
          return this.change(
            { user: c.to, role: 'operator', since: this.io.now() },
            user,
            'granted',
            `${user} gave control to ${c.to}`,
          );
        this.requests = this.requests.filter((r) => r !== c.to);
        this.event(user, 'refused', `${user} refused control to ${c.to}`);
        return this.announce();
      default: {
        const never: never = c;
        return never;
      }
    }
  }

  /** A new holder (or none): the arm stops, the lease restarts, the record is republished. */
  private change(next: Holder | null, by: string, kind: AuditKind, detail: string): void {
    if (this.current) this.io.forward(EMERGENCY_STOP);
    this.counters.handOvers++;
    this.lease.reset();
    this.current = next;
    if (next) {
      this.requests = this.requests.filter((r) => r !== next.user);
      this.lease.receive('1'); // held; the lease runs from its first beat
    } else this.requests = [];
    this.event(by, kind, detail);
    this.announce();
  }

  private refuseClaim(user: string, why: string): void {
    this.counters.refusedClaims++;
    this.event(user, 'refused-claim', why);
  }

  private event(by: string, kind: AuditKind, detail: string): void {
    this.io.audit({ at: Math.round(this.io.now()), by, kind, detail });
  }
}

/** Whether the payload holds `PDST` (a stop of some servo) anywhere: a cheap test before reading it. */
function mentionsStop(payload: Uint8Array | string): boolean {
  if (typeof payload === 'string') return payload.includes('PDST');
  for (let i = 0; i + 3 < payload.length; i++)
    if (
      payload[i] === 0x50 &&
      payload[i + 1] === 0x44 &&
      payload[i + 2] === 0x53 &&
      payload[i + 3] === 0x54
    )
      return true;
  return false;
}

interface Screened {
  /** Anything in it could move the arm: a move, a `$KMS`, a group, unreadable bytes. */
  blocked: boolean;
  /** Its stops, which are sent even when the rest is refused. */
  passed: string[];
  /** It holds `#255PDST!`. */
  emergencyStop: boolean;
}

/** Reads a control payload: whether it could move the arm, its stops, an emergency stop. */
function screen(payload: Uint8Array | string): Screened {
  let blocked = false;
  let emergencyStop = false;
  const passed: string[] = [];
  const reader = createReader({
    onFrame: (f) => {
      if (f.type === 'time') return;
      if (!ANYONE.has(f.type)) blocked = true;
      else if (f.type === 'stop') {
        passed.push(encodeFrame(f));
        if (f.id === SERVO_ID_ALL) emergencyStop = true;
      }
    },
    onGroup: () => void (blocked = true),
    onError: () => void (blocked = true),
  });
  reader.feed(payload);
  reader.flush();
  return { blocked, passed, emergencyStop };
}
