/**
 * Several brokers (PROTOCOL.md §9, docs/protocol.md § Several brokers): the ordered list every
 * part takes (`MQTT_URL`, `--mqtt`, the HUD's connection settings: comma-separated), and the
 * failover policy, pure (no sockets, no timers). The first broker is preferred; the others are
 * fall-backs. On losing its broker a part tries the next one in the list (wrapping round); while
 * on a fall-back it probes the first, and goes back to it once the first has answered
 * `returnAfterProbes` probes in a row. The I/O (an mqtt.js client whose reconnects follow this
 * policy, and the probes) is `connectBrokers.ts` beside it; this file has no I/O, so the page's
 * connection settings and the servers' options parse lists with it too.
 */

export interface BrokerListOptions {
  /** While on a fall-back, the first broker is probed this often, ms. */
  probeMs: number;
  /**
   * Probes in a row the first broker must answer before a part goes back to it (2: a flapping
   * broker is not chased). The middleware does not move: it is connected to every broker
   * (docs/protocol.md § Several brokers).
   */
  returnAfterProbes: number;
}

export const DEFAULT_BROKER_LIST_OPTIONS: BrokerListOptions = {
  probeMs: 2000,
  returnAfterProbes: 2,
};

/** Most brokers in one list. */
export const MAX_BROKERS = 8;

const SCHEMES = ['mqtt:', 'mqtts:', 'tcp:', 'ssl:', 'tls:', 'ws:', 'wss:'] as const;

/**
 * The ordered broker list in `text` (comma-separated; spaces around the commas ignored).
 * Throws an Error that names the bad entry: an empty list or entry, a URL that does not parse,
 * an unknown scheme, a duplicate, more than MAX_BROKERS. A page-relative `/mqtt` is accepted
 * when `relative` is set (the HUD's default is its own origin's `/mqtt`).
 */
export function parseBrokerList(text: string, relative = false): string[] {
  const entries = text.split(',').map((s) => s.trim());
  if (entries.length === 1 && entries[0] === '') throw new Error('no broker URL given');
  if (entries.length > MAX_BROKERS)
    throw new Error(`${entries.length} broker URLs given; at most ${MAX_BROKERS}`);
  const seen = new Set<string>();
  entries.forEach((url, i) => {
    const where = entries.length > 1 ? `broker ${i + 1} of ${entries.length}` : 'broker URL';
    if (url === '') throw new Error(`${where} is empty (two commas in a row?)`);
    if (seen.has(url)) throw new Error(`${where} (${url}) is listed twice`);
    seen.add(url);
    if (relative && url.startsWith('/')) return;
    let parsed: URL;
    try {
      parsed = new URL(url);
    } catch {
      throw new Error(`${where} is not a URL: "${url}"`);
    }
    if (!(SCHEMES as readonly string[]).includes(parsed.protocol))
      throw new Error(
        `${where} has scheme "${parsed.protocol}"; expected one of ${SCHEMES.join(' ')}`,
      );
  });
  return entries;
}

/** `ws://user:secret@host/…` → `ws://user:***@host/…` (for logs and the page). */
export function redactBrokerUrl(url: string): string {
  return url.replace(/^([a-z]+:\/\/[^:/@]*):[^@/]*@/i, '$1:***@');
}

/** Which broker a part uses, as the page shows it and the logs say it. */
export interface BrokerChoice {
  /** 0-based position in the list. */
  index: number;
  count: number;
  url: string;
}

/** "Broker 2 of 2: ws://…" (the password in the URL, if any, hidden). */
export const describeBroker = (b: BrokerChoice): string =>
  `Broker ${b.index + 1} of ${b.count}: ${redactBrokerUrl(b.url)}`;

/** A part began using another broker than before (one log line each). */
export interface BrokerMove {
  from: BrokerChoice | null;
  to: BrokerChoice;
  /** Why it left the previous one: it was lost, or the first answered again. */
  reason: 'lost' | 'first-back' | 'start';
}

/**
 * The failover state of one part. Its I/O edge tells it what happened (`connected`, `closed`,
 * `probed`) and asks it where to connect (`url`) and whether to probe (`probing`).
 */
export class BrokerFailover {
  readonly options: BrokerListOptions;
  /** The broker the next (or current) connection goes to. */
  private target = 0;
  /** The broker connected to now, -1 while none. */
  private current = -1;
  /** The broker last connected to (for the move record), -1 before the first. */
  private last = -1;
  private answers = 0;
  private returning = false;
  private pendingReason: BrokerMove['reason'] = 'start';
  /** Moves so far (not counting the first connection). */
  moves = 0;

  constructor(
    readonly urls: readonly string[],
    options: Partial<BrokerListOptions> = {},
  ) {
    if (urls.length === 0) throw new Error('no broker URL given');
    this.options = { ...DEFAULT_BROKER_LIST_OPTIONS, ...options };
  }

  /** Where the next connection attempt goes. */
  get url(): string {
    return this.urls[this.target]!;
  }

  /** The broker in use, or the one being tried while none is. */
  get choice(): BrokerChoice {
    const index = this.current >= 0 ? this.current : this.target;
    return { index, count: this.urls.length, url: this.urls[index]! };
  }

  /** Connected to some broker right now. */
  get isConnected(): boolean {
    return this.current >= 0;
  }

  /** On a fall-back: the first broker should be probed every `probeMs`. */
  get probing(): boolean {
    return this.current > 0;
  }

  /** The connection to `url` is up. Returns the move when this is another broker than before. */
  connected(): BrokerMove | null {
    this.current = this.target;
    this.answers = 0;
    const from = this.last;
    this.last = this.current;
    if (from === this.current) return null;
    if (from >= 0) this.moves++;
    return {
      from: from < 0 ? null : { index: from, count: this.urls.length, url: this.urls[from]! },
      to: this.choice,
      reason: from < 0 ? 'start' : this.pendingReason,
    };
  }

  /**
   * The connection closed, or an attempt failed: the next attempt goes to the next broker in
   * the list (wrapping round), unless a switch back to the first was asked for.
   */
  closed(): void {
    this.current = -1;
    this.answers = 0;
    if (this.returning) {
      this.returning = false; // the drop asked for by `probed`: the next attempt is the first's
      return;
    }
    this.pendingReason = 'lost';
    this.target = (this.target + 1) % this.urls.length;
  }

  /**
   * A probe of the first broker answered (`ok`) or not. True when the part should go back to it
   * now: the caller drops its connection, and the next attempt goes to the first broker.
   */
  probed(ok: boolean): boolean {
    if (!this.probing) return false;
    this.answers = ok ? this.answers + 1 : 0;
    if (this.answers < this.options.returnAfterProbes) return false;
    this.target = 0;
    this.returning = true;
    this.pendingReason = 'first-back';
    return true;
  }
}
