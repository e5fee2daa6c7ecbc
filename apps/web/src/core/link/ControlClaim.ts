/**
 * This page's side of "one operator at a time" (docs/protocol.md § Control): who holds the arm
 * (the controller's retained `arm/{id}/holder`), the events about this page's user
 * (`arm/{id}/audit`), and the claim words this page sends on `arm/{id}/claim/{name}`. The arm
 * enforces it; the page only mirrors it, so it never offers a move the arm would refuse.
 * A plain object: ArmLink feeds it messages and hands it a publish function; panels sample it.
 */
import {
  parseAudit,
  parseHolder,
  parseSummary,
  topic,
  userTopic,
  type AuditEvent,
  type HolderRecord,
} from '@armtwin/protocol';

export interface ControlIdentity {
  /** The name on this page's per-user topics. */
  name: string;
  /**
   * The broker vouches for the name (a logged-in user): commands always go on the user's own
   * control topic, and control is taken at log-in when nobody holds the arm. In the anonymous
   * demo the name is self-declared and the plain topic is used until the page takes control.
   */
  enforced: boolean;
  /** May take the arm outright, whoever holds it (`arm/{id}/override/{name}`). */
  admin: boolean;
}

/** A self-declared name for the anonymous demo: `guest-` and four hex digits. */
export function guestName(random: () => number = Math.random): string {
  return `guest-${Math.floor(random() * 0x10000)
    .toString(16)
    .padStart(4, '0')}`;
}

export class ControlClaim {
  /** Who holds the arm; null until the controller has said (an older controller never does). */
  holder: HolderRecord | null = null;
  /** The latest control event about this page's user, said on the page ('' = none). */
  notice: AuditEvent | null = null;
  private autoTaken = false;
  /** The retained record has come since the last connect or move (summaries then say nothing). */
  private recordCame = false;
  /** The time of the last summary taken (`t`, the arm's clock): an older one is stale. */
  private summaryAt = -Infinity;

  constructor(
    private readonly armId: string,
    readonly who: ControlIdentity,
    private readonly send: (topic: string, payload: string) => boolean,
    /** This page beats its claims (it holds the deadman; for a model copy, in Model mode). */
    private readonly beats: () => boolean = () => false,
  ) {}

  /** This page's user holds the arm. */
  get holding(): boolean {
    return this.holder?.user === this.who.name;
  }

  /** Who else holds the arm ('' when nobody, or this page's user, does). */
  get heldBy(): string {
    const u = this.holder?.user;
    return u && u !== this.who.name ? u : '';
  }

  /** Moves from this page would reach the arm (nobody else holds it). */
  get mayMove(): boolean {
    return this.heldBy === '';
  }

  /** This page's user is waiting for the holder's answer. */
  get asked(): boolean {
    return this.holder?.requests.includes(this.who.name) ?? false;
  }

  /** This page's commands and requests go on its user's own topics (logged in, or holding). */
  get ownTopics(): boolean {
    return this.who.enforced || this.holding;
  }

  /** Where this page's commands go: its own topic when logged in or holding, else the plain one. */
  get controlTopic(): string {
    return this.ownTopics
      ? userTopic(this.armId, 'control', this.who.name)
      : topic(this.armId, 'control');
  }

  /** Where this page's motion requests go, by the same rule as its commands. */
  get requestTopic(): string {
    return this.who.enforced || this.holding
      ? userTopic(this.armId, 'request', this.who.name)
      : topic(this.armId, 'request');
  }

  onHolder(payload: Uint8Array): void {
    const h = parseHolder(payload);
    if (!h) return;
    this.holder = h;
    this.recordCame = true;
    if (this.who.enforced && !this.autoTaken && h.user === null) {
      this.autoTaken = true; // control is taken on log-in when nobody holds it, once
      this.take();
    }
  }

  /**
   * The page moved to another broker: the holder it knew was the other broker's word, so it is
   * forgotten until this one's retained holder arrives. Control is not taken again on the
   * page's behalf (nor by the log-in's automatic take, if it had not happened yet).
   */
  moved(): void {
    this.holder = null;
    this.notice = null;
    this.recordCame = false;
    this.summaryAt = -Infinity;
    this.autoTaken = true; // no automatic take after a move: the operator takes control again
  }

  /**
   * The arm's summary (`arm/{id}/summary`, 2 Hz, docs/protocol.md § Fleets) names its holder:
   * until the retained holder record has come (after a connect or a move), it stands in for it,
   * with no requests. On a NATS cluster recovering from a lost node the record, when the page
   * read it through a QoS 1 subscription, took up to a minute (docs/cluster.md); both are QoS 0
   * now, and the summary still covers a record that comes late. It never makes the log-in's
   * automatic take: that waits for the record.
   */
  onSummary(payload: Uint8Array): void {
    if (this.recordCame) return;
    const r = parseSummary(payload);
    if (!r.ok || r.summary.t <= this.summaryAt) return;
    this.summaryAt = r.summary.t;
    const user = r.summary.holder;
    if (this.holder?.user !== user) this.holder = { user, requests: [] };
  }

  onAudit(payload: Uint8Array): void {
    const e = parseAudit(payload);
    if (!e) return;
    const me = this.who.name;
    const aboutMe = e.by === me || e.detail.split(/[\s:,;()]+/).includes(me);
    if (aboutMe) this.notice = e;
  }

  /**
   * Takes the arm: free, or (an administrator) from whoever holds it. A page that beats sends
   * its first `beat` right behind the take, so the holder's lease runs at once: a page whose
   * connection dies just after taking control loses the arm after the lease, where a holder
   * that has not beaten yet would keep it (docs/protocol.md § Control).
   */
  take(): boolean {
    const sent =
      this.heldBy && this.who.admin
        ? this.send(userTopic(this.armId, 'override', this.who.name), 'take')
        : this.claim('take');
    if (sent && this.beats()) this.claim('beat');
    return sent;
  }

  ask(): boolean {
    return this.claim('ask');
  }

  grant(user: string): boolean {
    return this.claim(`grant ${user}`);
  }

  refuse(user: string): boolean {
    return this.claim(`refuse ${user}`);
  }

  /** Lets go of the arm (or withdraws a request). */
  release(): boolean {
    return this.holding || this.asked ? this.claim('release') : false;
  }

  /** The holder's keep-alive (with the deadman's beat): a page that stops beating loses the arm. */
  beat(): void {
    if (this.holding) this.claim('beat');
  }

  /** `arm/{id}/claim/{name}`. */
  get claimTopic(): string {
    return userTopic(this.armId, 'claim', this.who.name);
  }

  private claim(words: string): boolean {
    return this.send(this.claimTopic, words);
  }
}
