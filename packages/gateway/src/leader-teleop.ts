/**
 * A leader arm as a teleoperation device (`armtwin gateway --bus feetech --leader-of ARM`), pure:
 * the leader's servo angles in, the follower's targets out, as its user's commands through the
 * follower's controller like any operator's (docs/protocol.md § Control). It takes the follower's
 * lease as `user` and beats it; each leader pose that moved goes as one angle-move group on
 * `arm/{follower}/control/{user}`, servo by servo of the same name (the follower's profile
 * announcement gives its ids), so the follower's controller checks limits and keep-out zones.
 * An emergency stop (an `e-stop` audit event), a lost lease or a refused take ends following: no
 * leader pose moves the follower again until its user re-enables it (`1` on the enable topic).
 * Every leader pose is announced on `arm/{follower}/leader/{user}` (`$TIM` + angle group) for the
 * HUD's ghost, and whether it follows (retained JSON) on `…/state`. Refusals are counted by kind.
 * The clock and publish are injected.
 */
import { parseAnnouncement } from '@armtwin/robot';
import {
  assertArmId,
  encodeAngle,
  encodeAngleMove,
  encodeGroup,
  encodeTime,
  leaderTopics as leaderOwnTopics,
  parseAudit,
  parseHolder,
  userTopic,
  type LeaderState,
} from '@armtwin/protocol';

/** The leader's topics under its follower: pose, state (retained), enable; and the follower's. */
export function leaderTopics(follower: string, user: string) {
  assertArmId(follower);
  return {
    ...leaderOwnTopics(follower, user),
    control: userTopic(follower, 'control', user),
    claim: userTopic(follower, 'claim', user),
    profile: `arm/${follower}/profile`,
    holder: `arm/${follower}/holder`,
    audit: `arm/${follower}/audit`,
  };
}

export interface LeaderTeleopIo {
  publish(topic: string, payload: string, opts: { qos: 0 | 1; retain: boolean }): void;
  /** Unix epoch ms. */
  now(): number;
  /** Told the first time each kind of problem happens. */
  onFirst(kind: string, message: string): void;
}

export interface LeaderTeleopOptions {
  follower: string;
  user: string;
  /** The leader's servos: bus id and name. */
  servos: readonly { id: number; name: string }[];
  /** A pose is sent when some servo moved at least this much since the last one sent, degrees. */
  deadbandDeg: number;
}

export const LEADER_DEADBAND_DEG = 0.1;

export class LeaderTeleop {
  readonly counters = {
    poses: 0,
    sent: 0,
    /** The follower's refusals of the leader's commands, by audit kind. */
    refused: {} as Record<string, number>,
    /** Messages that could not be read, by kind. */
    rejected: {} as Record<string, number>,
  };
  readonly topics;
  private following = true;
  private reason = '';
  private holding = false;
  private holder: string | null = null;
  /** Follower id by servo name (from its profile announcement). */
  private followerIds = new Map<string, number>();
  private lastSent: Map<number, number> | undefined;
  private readonly o: LeaderTeleopOptions;

  constructor(
    options: Omit<LeaderTeleopOptions, 'deadbandDeg'> & Partial<LeaderTeleopOptions>,
    private readonly io: LeaderTeleopIo,
  ) {
    this.o = { deadbandDeg: LEADER_DEADBAND_DEG, ...options };
    this.topics = leaderTopics(this.o.follower, this.o.user);
  }

  get state(): LeaderState {
    return { following: this.following, reason: this.reason };
  }

  /** The broker is (again) connected: take the follower if following. */
  connected(): void {
    if (this.following && !this.holding) this.claim('take');
    this.publishState();
  }

  /** Every `BEAT_MS` of the caller's timer: keeps the lease while holding. */
  beat(): void {
    if (this.holding) this.claim('beat');
  }

  /** The follower's retained profile announcement: its servo ids by name. */
  followerProfile(payload: string): void {
    const r = parseAnnouncement(payload);
    if (!r.ok) return this.reject('profile', r.error);
    const ids = new Map(r.profile.servos.map((s) => [s.name, s.id]));
    const missing = this.o.servos.filter((s) => !ids.has(s.name)).map((s) => s.name);
    this.followerIds = ids;
    if (missing.length) this.stop(`the follower has no servo named ${missing.join(', ')}`);
  }

  /** The follower's holder record. */
  holderRecord(payload: string): void {
    const h = parseHolder(payload);
    if (!h) return this.reject('holder', 'not a holder record');
    this.holder = h.user;
    const was = this.holding;
    this.holding = h.user === this.o.user;
    if (was && !this.holding)
      this.stop(h.user ? `control passed to ${h.user}` : 'the lease on the follower ended');
  }

  /** An event on the follower's audit topic. */
  audit(payload: string): void {
    const e = parseAudit(payload);
    if (!e) return this.reject('audit', 'not an audit event');
    if (e.kind === 'e-stop') this.stop(e.detail || `emergency stop by ${e.by || 'someone'}`);
    else if (e.by === this.o.user && e.kind.startsWith('refused')) {
      this.counters.refused[e.kind] = (this.counters.refused[e.kind] ?? 0) + 1;
      this.io.onFirst(`leader:${e.kind}`, `the follower refused the leader's pose: ${e.detail}`);
      if (e.kind === 'refused-claim')
        this.stop(
          `the follower is controlled by ${this.holder ?? 'someone else'}: ask for control`,
        );
    }
  }

  /** `1` on the enable topic: follow again (after a stop, or a lost lease). */
  enable(payload: string): void {
    if (payload.trim() !== '1') return this.reject('enable', 'expected 1');
    this.following = true;
    this.reason = '';
    this.lastSent = undefined;
    if (!this.holding) this.claim('take');
    this.publishState();
  }

  /** A read of the leader: announced, and sent to the follower when it moved and may be. */
  leaderPose(servos: readonly { id: number; degrees: number }[]): void {
    if (servos.length === 0) return;
    this.counters.poses++;
    const frames = servos.map((s) => encodeAngle(s.id, s.degrees));
    this.io.publish(this.topics.pose, encodeTime(Math.round(this.io.now())) + encodeGroup(frames), {
      qos: 0,
      retain: false,
    });
    if (!this.following || !this.holding || !this.moved(servos)) return;
    const moves: string[] = [];
    for (const s of servos) {
      const name = this.o.servos.find((l) => l.id === s.id)?.name;
      const id = name === undefined ? undefined : this.followerIds.get(name);
      if (id !== undefined) moves.push(encodeAngleMove(id, s.degrees, 0));
    }
    if (moves.length === 0) return;
    this.lastSent = new Map(servos.map((s) => [s.id, s.degrees]));
    this.counters.sent++;
    this.io.publish(this.topics.control, encodeGroup(moves), { qos: 0, retain: false });
  }

  /** Says it is gone (the caller's last will says the same if it dies). */
  release(): void {
    if (this.holding) this.claim('release');
    this.following = false;
    this.reason = 'the leader gateway stopped';
    this.publishState();
  }

  private moved(servos: readonly { id: number; degrees: number }[]): boolean {
    const last = this.lastSent;
    if (!last) return true;
    return servos.some(
      (s) => !(Math.abs(s.degrees - (last.get(s.id) ?? NaN)) < this.o.deadbandDeg),
    );
  }

  private stop(reason: string): void {
    if (!this.following) return;
    this.following = false;
    this.reason = `${reason}; publish 1 on ${this.topics.enable} to follow again`;
    this.io.onFirst(
      'leader:stopped',
      `the leader no longer drives ${this.o.follower}: ${this.reason}`,
    );
    this.publishState();
  }

  private claim(word: 'take' | 'beat' | 'release'): void {
    this.io.publish(this.topics.claim, word, { qos: 1, retain: false });
  }

  private publishState(): void {
    this.io.publish(this.topics.state, JSON.stringify(this.state), { qos: 1, retain: true });
  }

  private reject(kind: string, message: string): void {
    this.counters.rejected[kind] = (this.counters.rejected[kind] ?? 0) + 1;
    this.io.onFirst(`leader:bad-${kind}`, `leader: ${kind} ignored (${message})`);
  }
}
