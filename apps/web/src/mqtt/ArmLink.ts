/**
 * The HUD's MQTT edge: one mqtt.js client over WebSockets. Status messages go straight into
 * the store (no React); commands go out on `arm/{id}/control` at QoS 1. The client factory is
 * injected (./MqttLike.ts), so a unit test can hand in a fake and the page hands in mqtt.js.
 */
import {
  armTopics,
  auditTopic,
  holderTopic,
  EMERGENCY_STOP,
  angleFromPwm,
  encodeAngleMove,
  encodeKms,
  encodeMove,
  encodePing,
  encodeStop,
  OPERATOR_BEAT_MS,
  describeBroker,
  type ArmTopics,
} from '@armtwin/protocol';
import { findServo, isAngleWithinLimits, isWithinLimits, speaksAngle } from '@armtwin/ik';
import type { ArmStore } from '../store/ArmStore.ts';
import type { HudSettings } from '../config/settings.ts';
import { MoveCoalescer } from './MoveCoalescer.ts';
import { flushNow } from './flushNow.ts';
import { GapTracker } from './GapTracker.ts';
import { NO_PERMISSIONS, type LinkPermissions } from '../auth/roles.ts';
import { connectOptions } from './connectOptions.ts';
import type { MqttConnect, MqttLike } from './MqttLike.ts';
import { ControlClaim, guestName, type ControlIdentity } from './ControlClaim.ts';
import { ModelCopySide } from './ModelCopySide.ts';
import { commandTopic, modelArmId, stopArms, type ArmMode } from '../modes/modes.ts';

/** What the page hears from the link besides data (src/auth/Session.ts listens). */
export interface LinkEvents {
  connected?(): void;
  /** CONNACK 4/5: the broker refused these credentials (or none); reconnecting has stopped. */
  authRefused?(message: string): void;
}

/** A link started without a role (unit tests, scripts): commands and stop, no deadman. */
export const UNCHECKED_PERMISSIONS: LinkPermissions = { command: true, stop: true, deadman: false };

/**
 * Interval timers for the deadman's beat. The page passes worker-timers (as mqtt.js does for
 * its keep-alive), so a hidden tab keeps beating while a frozen one does not.
 */
export interface IntervalTimers {
  setInterval(fn: () => void, ms: number): number;
  clearInterval(id: number): void;
}
const NATIVE_INTERVALS: IntervalTimers = {
  setInterval: (fn, ms) => setInterval(fn, ms) as unknown as number,
  clearInterval: (id) => clearInterval(id),
};

const now = () => performance.now();
/** A payload of stops only: sent whoever holds the arm (the e-stop wins over everything). */
const STOPS_ONLY = /^(#\d{3}PDST!)+$/;
const decoder = new TextDecoder();

/**
 * Another reader of this link's client (the cameras of the arm, src/cameras/CameraHub.ts): its
 * filter is subscribed at every connect, with the link's log-in; matching messages go to it.
 */
export interface LinkTap {
  readonly filter: string;
  matches(topic: string): boolean;
  onMessage(topic: string, payload: Uint8Array): void;
}

export class ArmLink {
  readonly topics: ArmTopics;
  private client: MqttLike | null = null;
  private readonly coalescer: MoveCoalescer;
  private pingTimer: ReturnType<typeof setInterval> | undefined;
  private beatTimer: number | undefined;
  /** Bumped by every `$KMS` sent, so the Cartesian panel can match the reply. */
  kmsSent = 0;
  lastPublishError = '';
  /** Broker connection gaps (Status panel). */
  readonly gap = new GapTracker();
  /** What this page may publish; nothing until `start`. */
  permissions: LinkPermissions = NO_PERMISSIONS;
  private events: LinkEvents = {};
  private connected = false;
  private readonly taps: LinkTap[] = [];
  /** Who holds the real arm, and this page's claims on it (docs/protocol.md § Control). */
  private armClaim: ControlClaim;
  /** The arm's model copy `{id}-model`: read, claimed and held in Model mode (§ Modes). */
  private readonly copy: ModelCopySide;
  /**
   * Model / Shadow / Twin (../modes/modes.ts): which arm this page's commands drive. Every
   * command leaves through `publish`, which routes it by this, so no panel can bypass it.
   */
  private armMode: ArmMode = 'twin';
  /**
   * "Broker 2 of 2: ws://…" while connected with a list of several brokers, '' with one
   * (docs/protocol.md § Several brokers). Sampled by the Status panel.
   */
  brokerInUse = '';
  /** Moves to another broker of the list since `start`. */
  brokerMoves = 0;
  private brokerIndex = -1;

  constructor(
    private readonly store: ArmStore,
    readonly settings: HudSettings,
    private readonly connect: MqttConnect,
    private readonly intervals: IntervalTimers = NATIVE_INTERVALS,
  ) {
    this.topics = armTopics(settings.armId);
    const guest = { name: guestName(), enforced: false, admin: false };
    this.armClaim = this.controlFor(guest);
    const copyId = modelArmId(settings.armId);
    this.copy = new ModelCopySide(
      settings.armId,
      this.controlFor(guest, copyId ?? settings.armId),
      (message) => (this.store.connectionError = message),
      now,
    );
    this.coalescer = new MoveCoalescer((id, pwm) => this.sendMove(id, pwm), {
      intervalMs: settings.jogIntervalMs,
    });
  }

  /**
   * Connects. `permissions` (from the page's role, src/auth/roles.ts) decide what may be
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
      this.copy.claim = this.controlFor(who, this.copy.id ?? s.armId);
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
    client.on('connect', () => {
      this.store.connection = 'connected';
      this.store.connectionError = '';
      this.connected = true;
      this.onBroker(client);
      this.gap.restored(Date.now());
      if (deadman) this.holdOperator(client);
      this.events.connected?.();
      client.subscribe([this.topics.status, this.topics.online], { qos: 0 }, (err) => {
        if (err) this.store.connectionError = `subscribe failed: ${err.message}`;
      });
      client.subscribe([this.holderTopic, this.auditTopic], { qos: 1 }, (err) => {
        if (err) this.store.connectionError = `subscribe failed: ${err.message}`;
      });
      this.subscribeTaps(client);
      if (this.armMode === 'model') this.copy.enter(client, deadman);
      // Everyone's commands, for the predictive twin; a broker may refuse a role this (ACL).
      client.subscribe([`${this.topics.control}/#`], { qos: 0 }, () => {});
    });
    // A client this link has let go of (stop/release) still emits close/offline: the store is
    // the next link's by then, so those events are ignored.
    const current = () => this.client === client;
    client.on('reconnect', () => current() && (this.store.connection = 'reconnecting'));
    client.on('offline', () => {
      if (!current()) return;
      this.store.connection = 'offline';
      this.lost();
    });
    client.on('close', () => {
      if (!current()) return;
      if (this.store.connection === 'connected' || this.store.connection === 'connecting')
        this.store.connection = 'offline';
      this.lost();
    });
    client.on('error', (err) => {
      if (!current()) return;
      this.store.connection = 'error';
      this.store.connectionError = err.message;
      const code = (err as Error & { code?: unknown }).code;
      if (code === 4 || code === 5 || code === 134 || code === 135) {
        // mqtt.js stops reconnecting after a refused CONNACK; make sure of it.
        client.end(true);
        this.events.authRefused?.(err.message.replace(/^Connection refused: /, ''));
      }
    });
    // A client let go of may still deliver what was already in its socket: that is the previous
    // arm's data, and must not land in the store that now shows the next arm.
    client.on('message', (topic, payload) => current() && this.onMessage(topic, payload));
    this.pingTimer = setInterval(() => this.ping(), s.pingIntervalMs);
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
   * Which broker the client is on. After a move to another broker, what this page knew of the
   * holder came from the other one: it is forgotten until the new broker's retained holder
   * says, and control is never re-claimed on the page's behalf (docs/protocol.md § Several
   * brokers): the page holds the arm on the new broker only if the arm's controller still
   * counts it as holder, otherwise the operator takes control again.
   */
  private onBroker(client: MqttLike): void {
    const b = client.brokers?.choice;
    if (!b) return;
    this.brokerInUse = b.count > 1 ? describeBroker(b) : '';
    if (this.brokerIndex >= 0 && b.index !== this.brokerIndex) {
      this.brokerMoves++;
      this.armClaim.moved();
      this.copy.claim.moved();
    }
    this.brokerIndex = b.index;
  }

  /** Adds a reader of this link's messages (subscribed now when connected, else at connect). */
  tap(t: LinkTap): void {
    this.taps.push(t);
    if (this.client && this.connected) this.subscribeTaps(this.client, [t]);
  }

  private subscribeTaps(client: MqttLike, taps: readonly LinkTap[] = this.taps): void {
    if (taps.length === 0) return;
    client.subscribe(
      taps.map((t) => t.filter),
      { qos: 1 },
      (err) => {
        if (err) this.store.connectionError = `subscribe failed: ${err.message}`;
      },
    );
  }

  /**
   * A retained message at QoS 1 on a topic an operator may write besides the arm's control (a
   * camera's calibration, src/cameras/CameraHub.ts); false when not sent (no client, or a role
   * that may not command).
   */
  publishRetained(topic: string, payload: string): boolean {
    const client = this.client;
    if (!client || !this.permissions.command) return false;
    client.publish(topic, payload, { qos: 1, retain: true }, (err) => {
      if (err) this.lastPublishError = err.message;
    });
    return true;
  }

  /**
   * A bus arm's torque (`arm/{id}/torque`, QoS 1, not retained, so a restarted gateway starts
   * holding): `false` turns every servo limp, `true` holds where it is. False when not sent.
   */
  setTorque(on: boolean): boolean {
    const client = this.client;
    const arm = this.armMode === 'shadow' ? null : this.drivenArmId;
    if (!client || !this.permissions.command || arm === null) return false;
    client.publish(armTopics(arm).torque, on ? '1' : '0', { qos: 1 }, (err) => {
      if (err) this.lastPublishError = err.message;
    });
    return true;
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
   * Moves from this page would reach the driven arm: its role may command, the mode drives an
   * arm (not Shadow) and nobody else holds it.
   */
  get mayMove(): boolean {
    return this.permissions.command && this.armMode !== 'shadow' && this.control.mayMove;
  }

  /** Who holds the driven arm (the copy in Model mode), and this page's claims on it. */
  get control(): ControlClaim {
    return this.armMode === 'model' ? this.copy.claim : this.armClaim;
  }

  get mode(): ArmMode {
    return this.armMode;
  }

  /** The arm this page's commands drive now: the copy in Model mode, else the arm. */
  get drivenArmId(): string {
    return this.armMode === 'model' && this.copy.id ? this.copy.id : this.settings.armId;
  }

  /**
   * Switches what this page drives (../modes/ModeSwitch.ts calls it). Pending jogs are dropped.
   * Into Model: the copy's status, holder and audit are read (its status into `copy`) and the
   * page holds the copy's deadman while it is there; out of Model: the copy's deadman is let go
   * (a `0`, as the page's will would) and its claim released, and the copy is no longer read.
   */
  setMode(mode: ArmMode, copy: ArmStore | null = this.copy.store): void {
    if (mode === this.armMode || (mode === 'model' && !this.copy.id)) return;
    this.coalescer.cancelAll();
    const client = this.client;
    const was = this.armMode;
    this.armMode = mode;
    this.copy.store = copy;
    if (!client || !this.connected) return;
    if (mode === 'model') this.copy.enter(client, this.permissions.deadman);
    else if (was === 'model') this.copy.leave(client, this.permissions.deadman);
  }

  private get holderTopic(): string {
    return holderTopic(this.settings.armId);
  }

  private get auditTopic(): string {
    return auditTopic(this.settings.armId);
  }

  private controlFor(who: ControlIdentity, armId = this.settings.armId): ControlClaim {
    return new ControlClaim(armId, who, (topic, payload) => {
      const client = this.client;
      if (!client || !this.permissions.command) return false;
      client.publish(topic, payload, { qos: 1 }, (err) => {
        if (err) this.lastPublishError = err.message;
      });
      return true;
    });
  }

  private onMessage(topic: string, payload: Uint8Array): void {
    if (topic === this.topics.status) {
      this.store.ingest(payload, now());
    } else if (topic === this.topics.control || topic.startsWith(`${this.topics.control}/`)) {
      this.store.noteControl(payload, now());
    } else if (topic === this.holderTopic) {
      this.armClaim.onHolder(payload);
    } else if (topic === this.auditTopic) {
      this.armClaim.onAudit(payload);
    } else if (this.copy.onMessage(topic, payload)) {
      // the model copy's (Model mode)
    } else if (topic === this.topics.online) {
      const text = decoder.decode(payload).trim();
      this.store.armOnline = text === '1' ? true : text === '0' ? false : null;
      this.store.armOnlineText = this.store.armOnline === null ? text.slice(0, 80) : '';
    } else {
      for (const t of this.taps) if (t.matches(topic)) t.onMessage(topic, payload);
    }
  }

  /** The connection dropped: a gap starts (once), and the health charts get a break. */
  private lost(): void {
    this.connected = false;
    this.copy.lost();
    if (this.gap.lost(Date.now())) this.store.history.pushGap(Date.now() / 1000);
  }

  /**
   * Every command leaves here, routed by the mode (../modes/modes.ts `commandTopic`): to the
   * arm in Twin, to its copy in Model, nowhere in Shadow (stops included: the emergency stop
   * has its own route, `emergencyStop`).
   */
  private publish(payload: string, isCommand = true, allowed = this.permissions.command): boolean {
    const client = this.client;
    if (!client || !allowed) return false;
    const claim = this.control;
    const to = commandTopic(this.settings.armId, this.armMode, this.userOf(claim));
    if (to === null) {
      this.lastPublishError = 'not sent: Shadow mode sends no commands';
      return false;
    }
    if (isCommand && !claim.mayMove && !STOPS_ONLY.test(payload)) {
      this.lastPublishError = `not sent: ${claim.heldBy} controls the arm`;
      return false;
    }
    if (isCommand) this.store.counters.published++;
    // The predictive twin of the real arm hears only what goes to the real arm.
    (this.armMode === 'model' ? this.copy.store : this.store)?.noteControl(payload, now());
    client.publish(to, payload, { qos: 1 }, (err) => {
      if (err) this.lastPublishError = err.message;
    });
    return true;
  }

  /** The user of a claim's per-user topics, null for the plain topic (ControlClaim's rule). */
  private userOf(claim: ControlClaim): string | null {
    return claim.ownTopics ? claim.who.name : null;
  }

  /**
   * The servo angle to send instead of `pwm` when the servo speaks §8 angle frames (rounded to
   * the wire's 0.01°), NaN when it speaks pulses. `pwm` is then an exact pulse-equivalent.
   */
  private wireAngle(id: number, pwm: number): number {
    const spec = findServo(id, this.store.opts.arm);
    if (!speaksAngle(spec)) return NaN;
    return Math.round(angleFromPwm(pwm, spec!.polarity) * 100) / 100;
  }

  /** Whether a jog to `pwm` is within the servo's limits (in degrees for an angle servo). */
  private allowed(id: number, pwm: number): boolean {
    const arm = this.store.opts.arm;
    const deg = this.wireAngle(id, pwm);
    return Number.isNaN(deg) ? isWithinLimits(id, pwm, arm) : isAngleWithinLimits(id, deg, arm);
  }

  private sendMove(id: number, pwm: number): void {
    if (!this.allowed(id, pwm)) return; // never send an out-of-limit pulse or angle
    const ms = Math.round(this.settings.jogMoveMs);
    const deg = this.wireAngle(id, pwm);
    this.publish(Number.isNaN(deg) ? encodeMove(id, pwm, ms) : encodeAngleMove(id, deg, ms));
  }

  /** A slider moved: coalesced to at most one move per servo per jogIntervalMs. */
  jog(id: number, pwm: number): void {
    if (!this.allowed(id, pwm)) return;
    this.store.commandedPwm[id] = pwm;
    this.coalescer.request(id, pwm);
  }

  /**
   * `$KMS:x,y,z[,a],t!`. The caller has checked the target with the local IK, whose pulses for
   * servos 000–003 (`expectedPwm`) become the commanded pose the ghost shows.
   */
  moveTo(
    x: number,
    y: number,
    z: number,
    alpha: number | undefined,
    expectedPwm: ArrayLike<number>,
  ): void {
    for (let i = 0; i < 4; i++) this.store.commandedPwm[i] = expectedPwm[i] ?? NaN;
    this.kmsSent++;
    this.publish(encodeKms(x, y, z, Math.round(this.settings.kmsMoveMs), alpha));
  }

  /**
   * A hold-to-jog keep-alive (docs/protocol.md § Hold-to-jog): each servo to its pulse in `ms`,
   * one frame, or one `{…}` group for several (one command for the rate limit). A move outside
   * its servo's limits is never sent: then nothing is, and the answer is false.
   */
  holdMoves(moves: ReadonlyArray<readonly [id: number, pwm: number]>, ms: number): boolean {
    if (moves.length === 0 || !moves.every(([id, pwm]) => this.allowed(id, pwm))) return false;
    const t = Math.round(ms);
    const frames = moves.map(([id, pwm]) => {
      this.store.commandedPwm[id] = pwm;
      const deg = this.wireAngle(id, pwm);
      return Number.isNaN(deg) ? encodeMove(id, pwm, t) : encodeAngleMove(id, deg, t);
    });
    return this.publish(frames.length === 1 ? frames[0]! : `{${frames.join('')}}`);
  }

  /** `#IIIPDST!` for each servo, one payload (a hold-to-jog released); pending jogs dropped. */
  stopServos(ids: readonly number[]): boolean {
    if (ids.length === 0) return false;
    this.coalescer.cancelAll();
    for (const id of ids) this.store.commandedPwm[id] = NaN;
    return this.publish(ids.map(encodeStop).join(''), true, this.permissions.stop);
  }

  /** A `{…}` group of timed moves (a plan streamed by the Plan panel); false if not sent. */
  sendGroup(frame: string): boolean {
    return this.publish(frame);
  }

  /** Called first thing by `emergencyStop` (a streamed plan stops at once). */
  readonly stopListeners = new Set<() => void>();

  /**
   * `#255PDST!` at QoS 1, on the socket before this returns (./flushNow.ts); pending jogs (and a
   * streamed plan) are dropped first. Synchronous: nothing here waits for a frame or a promise.
   */
  emergencyStop(): boolean {
    for (const fn of this.stopListeners) fn();
    this.coalescer.cancelAll();
    this.store.commandedPwm.fill(NaN);
    const client = this.client;
    if (!client || !this.permissions.stop) return false;
    // The stop wins over every mode: the real arm always, and the copy too in Model mode.
    for (const arm of stopArms(this.settings.armId, this.armMode)) {
      const claim = arm === this.settings.armId ? this.armClaim : this.copy.claim;
      const to = commandTopic(arm, 'twin', this.userOf(claim));
      this.store.counters.published++;
      if (arm === this.settings.armId) this.store.noteControl(EMERGENCY_STOP, now());
      client.publish(to!, EMERGENCY_STOP, { qos: 1 }, (err) => {
        if (err) this.lastPublishError = err.message;
      });
    }
    flushNow(client);
    return true;
  }

  private ping(): void {
    if (this.store.connection !== 'connected' || !this.client || !this.permissions.command) return;
    // Pings measure the real arm's round trip: none in Model (the arm's control topics stay
    // silent while rehearsing) or Shadow (no commands at all).
    if (this.armMode !== 'twin') return;
    const seq = this.store.ping.send(now());
    this.publish(encodePing(seq), false);
  }

  /**
   * Lets go of the arm and disconnects: with the deadman, a retained `0` first (a moving arm
   * stops at once, as the will would make it), then a clean DISCONNECT. For pagehide.
   */
  release(): void {
    this.stopTimers();
    this.coalescer.cancelAll();
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
    this.coalescer.cancelAll();
    this.client?.end(true);
    this.client = null;
    this.store.connection = 'idle';
  }
}
