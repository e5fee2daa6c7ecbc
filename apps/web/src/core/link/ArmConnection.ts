/**
 * The arm link's connection (ArmLink, ./ArmLink.ts, holds one and adds the commands): one mqtt.js client over
 * WebSockets, its events (./clientEvents.ts), what it reads (./LinkInbox.ts), the broker it is on
 * (./BrokerTracker.ts), the deadman it holds, and this page's claims on the arm and on its model
 * copy, kept across reconnects. The client factory is injected (./MqttLike.ts), so a unit test
 * can hand in a fake and the page hands in mqtt.js.
 */
import { armTopics, OPERATOR_BEAT_MS, type ArmTopics } from '@armtwin/protocol';
import type { ArmStore } from '../store/ArmStore.ts';
import type { HudSettings } from '../config/settings.ts';
import { GapTracker } from './GapTracker.ts';
import { NO_PERMISSIONS, type LinkPermissions } from './permissions.ts';
import { connectOptions } from './connectOptions.ts';
import type { MqttConnect, MqttLike } from './MqttLike.ts';
import { ControlClaim, guestName, type ControlIdentity } from './ControlClaim.ts';
import { ModelCopySide } from './ModelCopySide.ts';
import { modelArmId, type ArmMode } from './modes.ts';
import { NATIVE_INTERVALS, type IntervalTimers } from './intervalTimers.ts';
import { BrokerTracker } from './BrokerTracker.ts';
import { wireClient } from './clientEvents.ts';
import { OwnEchoes } from './OwnEchoes.ts';
import { LinkInbox, type LinkTap } from './LinkInbox.ts';

/** What the page hears from the link besides data (src/core/auth/Session.ts listens). */
export interface LinkEvents {
  connected?(): void;
  /** CONNACK 4/5: the broker refused these credentials (or none); reconnecting has stopped. */
  authRefused?(message: string): void;
}

/** A link started without a role (unit tests, scripts): commands and stop, no deadman. */
export const UNCHECKED_PERMISSIONS: LinkPermissions = { command: true, stop: true, deadman: false };

/** The link's clock for the store and its commands: ms, `performance.now()`. */
export const now = () => performance.now();

/** What the connection calls back into its owner (ArmLink): the ping, and pending moves dropped. */
export interface ConnectionHooks {
  /** Every settings.pingIntervalMs while started. */
  ping(): void;
  /** On release and stop: the moves waiting to go out are dropped. */
  dropPending(): void;
}

export class ArmConnection {
  readonly topics: ArmTopics;
  /** The mqtt.js client while started (replaced at each start), else null. */
  client: MqttLike | null = null;
  private pingTimer: ReturnType<typeof setInterval> | undefined;
  private beatTimer: number | undefined;
  lastPublishError = '';
  /** Broker connection gaps (Status panel). */
  readonly gap = new GapTracker();
  /** What this page may publish; nothing until `start`. */
  permissions: LinkPermissions = NO_PERMISSIONS;
  private events: LinkEvents = {};
  connected = false;
  /** Who holds the real arm, and this page's claims on it (docs/protocol.md § Control). */
  armClaim: ControlClaim;
  /** The arm's model copy `{id}-model`: read, claimed and held in Model mode (§ Modes). */
  readonly copy: ModelCopySide;
  /**
   * Model / Shadow / Twin (./modes.ts): which arm this page's commands drive. Every
   * command leaves through ArmLink's `publish`, which routes it by this, so no panel can bypass it.
   */
  armMode: ArmMode = 'twin';
  private readonly brokers = new BrokerTracker();
  private readonly inbox: LinkInbox;
  /** The commands this page sent, so their echo is not a second command (./OwnEchoes.ts). */
  readonly own = new OwnEchoes();
  /** The callback of every publish: a failure is kept for the Status panel. */
  readonly onPublished = (err?: Error) => {
    if (err) this.lastPublishError = err.message;
  };

  constructor(
    readonly store: ArmStore,
    readonly settings: HudSettings,
    private readonly connect: MqttConnect,
    private readonly hooks: ConnectionHooks,
    private readonly intervals: IntervalTimers = NATIVE_INTERVALS,
  ) {
    this.topics = armTopics(settings.armId);
    const guest = { name: guestName(), enforced: false, admin: false };
    this.armClaim = this.controlFor(guest);
    const copyId = modelArmId(settings.armId);
    const onError = (message: string) => (this.store.connectionError = message);
    this.copy = new ModelCopySide(settings.armId, this.controlFor(guest, copyId), onError, now);
    this.inbox = new LinkInbox(
      settings.armId,
      this.topics,
      store,
      () => this.armClaim,
      this.copy,
      (err) => err && onError(`subscribe failed: ${err.message}`),
      now,
      this.own,
    );
  }

  /**
   * "Broker 2 of 2: ws://…" while connected with a list of several brokers, '' with one
   * (docs/protocol.md § Several brokers). Sampled by the Status panel.
   */
  get brokerInUse(): string {
    return this.brokers.inUse;
  }

  /** Moves to another broker of the list since `start`. */
  get brokerMoves(): number {
    return this.brokers.moves;
  }

  /**
   * Connects. `permissions` (from the page's role, src/core/auth/roles.ts) decide what may be
   * published; with `deadman` the page holds `arm/{id}/operator`: a short keep-alive
   * (settings.deadmanKeepAliveS), a retained `1` at every connect and every OPERATOR_BEAT_MS
   * after (the lease a controller watches, docs/protocol.md), and a last will `0`.
   */
  start(
    permissions: LinkPermissions = UNCHECKED_PERMISSIONS,
    events: LinkEvents = {},
    who?: ControlIdentity,
  ): void {
    const s = this.settings;
    this.permissions = permissions;
    if (who) {
      this.armClaim = this.controlFor(who);
      this.copy.claim = this.controlFor(who, this.copy.id);
    }
    this.events = events;
    this.store.connection = 'connecting';
    const deadman = permissions.deadman;
    const client = this.connect(s.brokerUrl, {
      ...connectOptions(
        'hud',
        s,
        deadman ? { keepalive: Math.max(1, Math.round(s.deadmanKeepAliveS)) } : {},
      ),
      ...(deadman
        ? { will: { topic: this.topics.operator, payload: '0', qos: 1, retain: true } }
        : {}),
    });
    this.client = client;
    const current = () => this.client === client;
    wireClient(client, current, this.store, {
      connected: () => this.onConnect(client, deadman),
      lost: () => this.lost(),
      authRefused: (message) => this.events.authRefused?.(message),
      message: (topic, payload) => this.inbox.onMessage(topic, payload),
    });
    this.pingTimer = setInterval(() => this.hooks.ping(), s.pingIntervalMs);
    if (deadman)
      this.beatTimer = this.intervals.setInterval(() => {
        if (!this.connected || !current()) return;
        this.holdOperator(client);
        this.armClaim.beat();
        if (this.armMode === 'model') {
          this.copy.holdOperator(client, '1');
          this.copy.claim.beat();
        }
      }, OPERATOR_BEAT_MS);
  }

  /**
   * Connected (at first, or again). After a move to another broker, what this page knew of the
   * holder came from the other one: it is forgotten until the new broker's retained holder
   * says, and control is never re-claimed on the page's behalf (docs/protocol.md § Several
   * brokers): the page holds the arm on the new broker only if the arm's controller still
   * counts it as holder, otherwise the operator takes control again.
   */
  private onConnect(client: MqttLike, deadman: boolean): void {
    this.connected = true;
    if (this.brokers.connectedTo(client.brokers?.choice)) {
      this.armClaim.moved();
      this.copy.claim.moved();
    }
    this.gap.restored(Date.now());
    if (deadman) this.holdOperator(client);
    this.events.connected?.();
    this.inbox.subscribe(client, this.armMode === 'model', deadman);
  }

  /** Adds a reader of this link's messages (subscribed now when connected, else at connect). */
  tap(t: LinkTap): void {
    this.inbox.tap(t, this.connected ? this.client : null);
  }

  /** The deadman's `1`: retained, QoS 1 (at connect, then as the beat). */
  private holdOperator(client: MqttLike): void {
    client.publish(this.topics.operator, '1', { qos: 1, retain: true });
  }

  private stopTimers(): void {
    clearInterval(this.pingTimer);
    if (this.beatTimer !== undefined) this.intervals.clearInterval(this.beatTimer);
    this.beatTimer = undefined;
  }

  /**
   * This page's claims on the arm, or (`copyId`) on its model copy. They beat with the
   * deadman's timer: the arm's whenever the page holds the deadman, the copy's in Model mode.
   */
  private controlFor(who: ControlIdentity, copyId?: string | null): ControlClaim {
    const send = (topic: string, payload: string) => {
      const client = this.client;
      if (!client || !this.permissions.command) return false;
      client.publish(topic, payload, { qos: 1 }, this.onPublished);
      return true;
    };
    if (copyId === undefined)
      return new ControlClaim(this.settings.armId, who, send, () => this.permissions.deadman);
    const beats = () => this.permissions.deadman && this.armMode === 'model';
    return new ControlClaim(copyId ?? this.settings.armId, who, send, beats);
  }

  /** The connection dropped: a gap starts (once), and the health charts get a break. */
  private lost(): void {
    this.connected = false;
    this.copy.lost();
    if (this.gap.lost(Date.now())) this.store.history.pushGap(Date.now() / 1000);
  }

  /**
   * Lets go of the arm and disconnects: with the deadman, a retained `0` first (a moving arm
   * stops at once, as the will would make it), then a clean DISCONNECT. For pagehide.
   */
  release(): void {
    this.stopTimers();
    this.hooks.dropPending();
    const client = this.client;
    this.client = null;
    if (!client) return;
    if (this.connected && this.armClaim.holding)
      client.publish(this.armClaim.claimTopic, 'release', { qos: 1 });
    if (this.connected && this.copy.claim.holding)
      client.publish(this.copy.claim.claimTopic, 'release', { qos: 1 });
    if (this.permissions.deadman && this.connected)
      client.publish(this.topics.operator, '0', { qos: 1, retain: true });
    if (this.permissions.deadman && this.connected && this.armMode === 'model')
      this.copy.holdOperator(client, '0');
    client.end(false);
    this.store.connection = 'idle';
  }

  stop(): void {
    if (this.permissions.deadman && this.connected) return this.release();
    this.stopTimers();
    this.hooks.dropPending();
    this.client?.end(true);
    this.client = null;
    this.store.connection = 'idle';
  }
}
