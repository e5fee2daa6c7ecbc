/**
 * The HUD's MQTT link to one arm. Status messages go straight into the store (no React);
 * commands go out on `arm/{id}/control` at QoS 1. This file holds the commands: their routing
 * by mode (./commandRoute.ts), the jogs' coalescing and frames (./moveFrames.ts) and the
 * emergency stop. The connection they leave on (./ArmConnection.ts) is a part it holds, not a
 * base class: the page reads the connection's figures through the getters below.
 */
import { armTopics, EMERGENCY_STOP, encodeKms, encodePing, encodeStop } from '@armtwin/protocol';
import type { ArmStore } from '../store/ArmStore.ts';
import type { HudSettings } from '../config/settings.ts';
import { MoveCoalescer } from './MoveCoalescer.ts';
import { flushNow } from './flushNow.ts';
import type { MqttConnect } from './MqttLike.ts';
import type { ControlClaim } from './ControlClaim.ts';
import { commandTopic, stopArms, type ArmMode } from './modes.ts';
import type { IntervalTimers } from './intervalTimers.ts';
import type { ArmCommands } from './ArmCommands.ts';
import { ArmConnection, now, type LinkEvents } from './ArmConnection.ts';
import type { ControlIdentity } from './ControlClaim.ts';
import type { LinkTap } from './LinkInbox.ts';
import type { GapTracker } from './GapTracker.ts';
import type { LinkPermissions } from './permissions.ts';
import type { MqttLike } from './MqttLike.ts';
import { moveAllowed, moveFrame, movesFrame } from './moveFrames.ts';
import { claimUser, routeCommand } from './commandRoute.ts';

export type { IntervalTimers, LinkTap, LinkEvents };
export { UNCHECKED_PERMISSIONS } from './ArmConnection.ts';

export class ArmLink implements ArmCommands {
  private readonly coalescer: MoveCoalescer;
  /** The MQTT client, the deadman, the claims, what is read: ./ArmConnection.ts. */
  private readonly conn: ArmConnection;
  /** Bumped by every `$KMS` sent, so the Cartesian panel can match the reply. */
  kmsSent = 0;

  constructor(
    private readonly store: ArmStore,
    readonly settings: HudSettings,
    connect: MqttConnect,
    intervals?: IntervalTimers,
  ) {
    this.conn = new ArmConnection(
      store,
      settings,
      connect,
      { ping: () => this.ping(), dropPending: () => this.coalescer.cancelAll() },
      intervals,
    );
    this.coalescer = new MoveCoalescer((id, pwm) => this.sendMove(id, pwm), {
      intervalMs: settings.jogIntervalMs,
    });
  }

  /** Connects with what the role may publish (ArmConnection.start). */
  start(permissions?: LinkPermissions, events?: LinkEvents, who?: ControlIdentity): void {
    this.conn.start(permissions, events, who);
  }

  /** Lets go of the arm (the deadman's `0`) and disconnects: for pagehide. */
  release(): void {
    this.conn.release();
  }

  stop(): void {
    this.conn.stop();
  }

  /** Adds a reader of this link's messages. */
  tap(t: LinkTap): void {
    this.conn.tap(t);
  }

  get topics() {
    return this.conn.topics;
  }

  /** What this page may publish; nothing until `start`. */
  get permissions(): LinkPermissions {
    return this.conn.permissions;
  }

  /** Broker connection gaps (Status panel). */
  get gap(): GapTracker {
    return this.conn.gap;
  }

  get lastPublishError(): string {
    return this.conn.lastPublishError;
  }

  get brokerInUse(): string {
    return this.conn.brokerInUse;
  }

  get brokerMoves(): number {
    return this.conn.brokerMoves;
  }

  /** The client while started (the debug hook's; a test plays a tampered page with it). */
  get client(): MqttLike | null {
    return this.conn.client;
  }

  private get armMode(): ArmMode {
    return this.conn.armMode;
  }

  private get copy() {
    return this.conn.copy;
  }

  private get onPublished() {
    return this.conn.onPublished;
  }

  /**
   * A retained message at QoS 1 on a topic an operator may write besides the arm's control (a
   * camera's calibration, src/core/cameras/CameraHub.ts); false when not sent (no client, or a role
   * that may not command).
   */
  publishRetained(topic: string, payload: string): boolean {
    const client = this.client;
    if (!client || !this.permissions.command) return false;
    client.publish(topic, payload, { qos: 1, retain: true }, this.onPublished);
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
    client.publish(armTopics(arm).torque, on ? '1' : '0', { qos: 1 }, this.onPublished);
    return true;
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
    return this.armMode === 'model' ? this.copy.claim : this.conn.armClaim;
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
    this.conn.armMode = mode;
    this.copy.store = copy;
    if (!client || !this.conn.connected) return;
    if (mode === 'model') this.copy.enter(client, this.permissions.deadman);
    else if (was === 'model') this.copy.leave(client, this.permissions.deadman);
  }

  /**
   * Every command leaves here, routed by the mode (./commandRoute.ts): to the arm in Twin, to
   * its copy in Model, nowhere in Shadow (stops included: the emergency stop has its own route,
   * `emergencyStop`).
   */
  private publish(payload: string, isCommand = true, allowed = this.permissions.command): boolean {
    const client = this.client;
    if (!client || !allowed) return false;
    const route = routeCommand(this.settings.armId, this.armMode, this.control, payload, isCommand);
    if (route.to === null) {
      this.conn.lastPublishError = route.refused;
      return false;
    }
    if (isCommand) this.store.counters.published++;
    // The predictive twin of the real arm hears only what goes to the real arm.
    const t = now();
    (this.armMode === 'model' ? this.copy.store : this.store)?.noteControl(payload, t);
    this.conn.own.note(route.to, payload, t);
    client.publish(route.to, payload, { qos: 1 }, this.onPublished);
    return true;
  }

  private sendMove(id: number, pwm: number): void {
    const arm = this.store.opts.arm;
    if (!moveAllowed(id, pwm, arm)) return; // never send an out-of-limit pulse or angle
    this.publish(moveFrame(id, pwm, Math.round(this.settings.jogMoveMs), arm));
  }

  /** A slider moved: coalesced to at most one move per servo per jogIntervalMs. */
  jog(id: number, pwm: number): void {
    if (!moveAllowed(id, pwm, this.store.opts.arm)) return;
    this.store.setCommanded(id, pwm);
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
    const arm = this.store.opts.arm;
    if (moves.length === 0 || !moves.every(([id, pwm]) => moveAllowed(id, pwm, arm))) return false;
    for (const [id, pwm] of moves) this.store.setCommanded(id, pwm);
    return this.publish(movesFrame(moves, Math.round(ms), arm));
  }

  /** `#IIIPDST!` for each servo, one payload (a hold-to-jog released); pending jogs dropped. */
  stopServos(ids: readonly number[]): boolean {
    if (ids.length === 0) return false;
    this.coalescer.cancelAll();
    for (const id of ids) this.store.setCommanded(id, NaN);
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
      const claim = arm === this.settings.armId ? this.conn.armClaim : this.copy.claim;
      const to = commandTopic(arm, 'twin', claimUser(claim));
      this.store.counters.published++;
      if (arm === this.settings.armId) {
        const t = now();
        this.store.noteControl(EMERGENCY_STOP, t);
        this.conn.own.note(to!, EMERGENCY_STOP, t);
      }
      client.publish(to!, EMERGENCY_STOP, { qos: 1 }, this.onPublished);
    }
    flushNow(client);
    return true;
  }

  /** A `$PNG` (ArmConnection's timer calls it). */
  private ping(): void {
    if (this.store.connection !== 'connected' || !this.client || !this.permissions.command) return;
    // Pings measure the real arm's round trip: none in Model (the arm's control topics stay
    // silent while rehearsing) or Shadow (no commands at all).
    if (this.armMode !== 'twin') return;
    const seq = this.store.ping.send(now());
    this.publish(encodePing(seq), false);
  }
}
