/**
 * The leader arms of the selected arm (docs/so101.md § 6): each leader gateway's pose on
 * `arm/{id}/leader/{user}` and whether it drives the arm on `…/state` (retained), read on the arm
 * link's client (rebuilt for each arm and log-in, so the leaders follow the selected arm; every
 * role may read them). The newest fresh pose is the ghost's (a `GhostSource`: where the leader
 * asks the arm to go, servo by servo of the same id, filled into the store's slots with no
 * allocation); panels sample `list`, `version` and `rejected`. Unreadable messages are counted by
 * kind. Plain state, no React; the clock is the caller's (`now`, ms).
 */
import {
  angleFromPwm,
  createReader,
  leaderPoseFilter,
  leaderStateFilter,
  parseLeaderState,
  parseLeaderTopic,
  type Frame,
  type LeaderState,
} from '@armtwin/protocol';
import { servoSlots } from '../store/servoSlots.ts';
import type { GhostSource } from '../store/viewSources.ts';
import type { LinkTap } from '../link/LinkInbox.ts';
import type { HudSettings } from '../config/settings.ts';

/** A leader's pose older than this is not shown (its gateway stopped reading, or is gone), ms. */
export const LEADER_POSE_FRESH_MS = 2000;

/** What can be wrong with a leader message, counted on the page. */
export type LeaderRejection = 'pose' | 'state' | 'servo';

/** One leader as the panels show it. */
export interface LeaderView {
  user: string;
  /** Its retained state, null before one came. */
  state: LeaderState | null;
  /** When its last pose arrived (the caller's clock), NaN = none yet. */
  poseAt: number;
}

/** The part of the arm link the feed uses. */
export interface LeaderLink {
  readonly settings: Pick<HudSettings, 'armId'>;
  tap(t: LinkTap): void;
}

interface Leader extends LeaderView {
  /** The last pose: degrees by frame id (NaN = not in it). */
  deg: Float64Array;
}

type Servos = readonly { readonly id: number; readonly polarity: number }[];

export class LeaderFeed implements GhostSource {
  /** Bumped when a leader appears or its state changes (not by its poses). */
  version = 0;
  readonly rejected: Record<LeaderRejection, number> = { pose: 0, state: 0, servo: 0 };
  /** The user whose pose the ghost showed at its last `sample` ('' = none). */
  onGhost = '';
  private readonly leaders = new Map<string, Leader>();
  private armId = '';
  private slotsOf: Servos | null = null;
  private slots: Int16Array = new Int16Array(0);
  private taking: Leader | null = null;
  private bad = false;
  private readonly reader = createReader({
    onFrame: (f) => this.frame(f),
    onGroup: (g) => g.frames.forEach((f) => this.frame(f)),
    onError: () => (this.bad = true),
  });

  constructor(
    /** The store arm's servos now (their ids give the slots, their polarities read pulses). */
    private readonly servos: () => Servos,
    private readonly now: () => number,
  ) {}

  /** Follows the leaders of `link`'s arm; the previous arm's are forgotten. */
  attach(link: LeaderLink): void {
    const armId = (this.armId = link.settings.armId);
    if (this.leaders.size > 0) this.version++;
    this.leaders.clear();
    const kinds = [
      ['pose', leaderPoseFilter(armId)],
      ['state', leaderStateFilter(armId)],
    ] as const;
    for (const [kind, filter] of kinds)
      link.tap({
        filter,
        matches: (topic) => {
          const t = parseLeaderTopic(topic);
          return t?.armId === armId && t.kind === kind;
        },
        onMessage: (topic, payload) => armId === this.armId && this.take(topic, payload),
      });
  }

  /** The leaders seen, by user. */
  get list(): LeaderView[] {
    return [...this.leaders.values()]
      .sort((a, b) => a.user.localeCompare(b.user))
      .map(({ user, state, poseAt }) => ({ user, state, poseAt }));
  }

  /** A message on one of the leader topics of the arm. */
  take(topic: string, payload: Uint8Array | string): void {
    const t = parseLeaderTopic(topic);
    if (!t || t.armId !== this.armId || t.kind === 'enable') return;
    const leader = this.leader(t.user);
    if (t.kind === 'state') {
      const s = parseLeaderState(payload);
      if ('error' in s) return void this.rejected.state++;
      leader.state = s;
      this.version++;
      return;
    }
    this.taking = leader;
    this.bad = false;
    leader.deg.fill(NaN);
    this.reader.feed(payload);
    this.reader.flush(); // a cut-off frame is bad input too
    this.reader.reset();
    this.taking = null;
    if (this.bad) this.rejected.pose++;
    leader.poseAt = this.now();
  }

  /** The ghost: the newest fresh leader pose in the store's slots (NaN where it has none). */
  sample(now: number, out: Float64Array): boolean {
    let newest: Leader | null = null;
    for (const l of this.leaders.values())
      if (now - l.poseAt <= LEADER_POSE_FRESH_MS && !(l.poseAt <= (newest?.poseAt ?? -Infinity)))
        newest = l;
    this.onGhost = newest?.user ?? '';
    if (!newest) return false;
    const slots = this.slotTable();
    out.fill(NaN);
    for (let id = 0; id < newest.deg.length; id++) {
      const d = newest.deg[id]!;
      const i = slots[id] ?? -1;
      if (!Number.isNaN(d) && i >= 0 && i < out.length) out[i] = d;
    }
    return true;
  }

  /** The ghost shows something else (a plan, the calibration): no leader is on it. */
  notShown(): true {
    this.onGhost = '';
    return true;
  }

  private leader(user: string): Leader {
    let l = this.leaders.get(user);
    if (!l) {
      l = { user, state: null, poseAt: NaN, deg: new Float64Array(256).fill(NaN) };
      this.leaders.set(user, l);
      this.version++;
    }
    return l;
  }

  private frame(f: Frame): void {
    const l = this.taking;
    if (!l) return;
    if (f.type !== 'angle' && f.type !== 'position') return;
    const i = this.slotTable()[f.id] ?? -1;
    if (i < 0) return void this.rejected.servo++;
    l.deg[f.id] =
      f.type === 'angle' ? f.deg : angleFromPwm(f.pwm, this.servos()[i]?.polarity === -1 ? -1 : 1);
  }

  private slotTable(): Int16Array {
    const servos = this.servos();
    if (servos !== this.slotsOf) {
      this.slotsOf = servos;
      this.slots = servoSlots(servos);
    }
    return this.slots;
  }
}
