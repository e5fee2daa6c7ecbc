/**
 * The HUD's MQTT edge: one mqtt.js client over WebSockets. Status messages go straight into
 * the store (no React); commands go out on `arm/{id}/control` at QoS 1. The client factory is
 * injected, so a unit test can hand in a fake and the page hands in mqtt.js.
 */
import {
  armTopics,
  EMERGENCY_STOP,
  encodeKms,
  encodeMove,
  encodePing,
  type ArmTopics,
} from '@armtwin/protocol';
import { isWithinLimits } from '@armtwin/ik';
import type { ArmStore } from '../store/ArmStore.ts';
import type { HudSettings } from '../config/settings.ts';
import { MoveCoalescer } from './MoveCoalescer.ts';

/** The part of mqtt.js's MqttClient this module uses. */
export interface MqttLike {
  on(event: 'connect' | 'reconnect' | 'close' | 'offline' | 'end', cb: () => void): unknown;
  on(event: 'error', cb: (err: Error) => void): unknown;
  on(event: 'message', cb: (topic: string, payload: Uint8Array) => void): unknown;
  subscribe(topics: string[], opts: { qos: 0 | 1 }, cb?: (err: Error | null) => void): unknown;
  publish(
    topic: string,
    payload: string,
    opts: { qos: 0 | 1; retain?: boolean },
    cb?: (err?: Error) => void,
  ): unknown;
  end(force?: boolean): unknown;
}

export interface ConnectOptions {
  clientId: string;
  username?: string;
  password?: string;
  keepalive: number;
  reconnectPeriod: number;
  connectTimeout: number;
  clean: boolean;
}

export type MqttConnect = (url: string, opts: ConnectOptions) => MqttLike;

/** Contract §6: keep-alive 60 s, reconnect every 1000 ms. */
const KEEPALIVE_S = 60;
const RECONNECT_MS = 1000;

const now = () => performance.now();

export class ArmLink {
  readonly topics: ArmTopics;
  private client: MqttLike | null = null;
  private readonly coalescer: MoveCoalescer;
  private pingTimer: ReturnType<typeof setInterval> | undefined;
  /** Bumped by every `$KMS` sent, so the Cartesian panel can match the reply. */
  kmsSent = 0;
  lastPublishError = '';

  constructor(
    private readonly store: ArmStore,
    readonly settings: HudSettings,
    private readonly connect: MqttConnect,
  ) {
    this.topics = armTopics(settings.armId);
    this.coalescer = new MoveCoalescer((id, pwm) => this.sendMove(id, pwm), {
      intervalMs: settings.jogIntervalMs,
    });
  }

  start(): void {
    const s = this.settings;
    this.store.connection = 'connecting';
    const client = this.connect(s.brokerUrl, {
      clientId: `armtwin-hud-${Math.random().toString(16).slice(2, 10)}`,
      ...(s.username ? { username: s.username } : {}),
      ...(s.password ? { password: s.password } : {}),
      keepalive: KEEPALIVE_S,
      reconnectPeriod: RECONNECT_MS,
      connectTimeout: 10_000,
      clean: true,
    });
    this.client = client;
    client.on('connect', () => {
      this.store.connection = 'connected';
      this.store.connectionError = '';
      client.subscribe([this.topics.status, this.topics.online], { qos: 0 }, (err) => {
        if (err) this.store.connectionError = `subscribe failed: ${err.message}`;
      });
    });
    client.on('reconnect', () => (this.store.connection = 'reconnecting'));
    client.on('offline', () => (this.store.connection = 'offline'));
    client.on('close', () => {
      if (this.store.connection === 'connected' || this.store.connection === 'connecting')
        this.store.connection = 'offline';
    });
    client.on('error', (err) => {
      this.store.connection = 'error';
      this.store.connectionError = err.message;
    });
    client.on('message', (topic, payload) => this.onMessage(topic, payload));
    this.pingTimer = setInterval(() => this.ping(), s.pingIntervalMs);
  }

  private onMessage(topic: string, payload: Uint8Array): void {
    if (topic === this.topics.status) {
      this.store.ingest(payload, now());
    } else if (topic === this.topics.online) {
      const text = new TextDecoder().decode(payload).trim();
      this.store.armOnline = text === '1' ? true : text === '0' ? false : null;
    }
  }

  private publish(payload: string, isCommand = true): boolean {
    const client = this.client;
    if (!client) return false;
    if (isCommand) this.store.counters.published++;
    client.publish(this.topics.control, payload, { qos: 1 }, (err) => {
      if (err) this.lastPublishError = err.message;
    });
    return true;
  }

  private sendMove(id: number, pwm: number): void {
    if (!isWithinLimits(id, pwm, this.store.opts.arm)) return; // never send an out-of-limit pulse
    this.publish(encodeMove(id, pwm, Math.round(this.settings.jogMoveMs)));
  }

  /** A slider moved: coalesced to at most one move per servo per jogIntervalMs. */
  jog(id: number, pwm: number): void {
    if (!isWithinLimits(id, pwm, this.store.opts.arm)) return;
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

  /** `#255PDST!` at QoS 1; pending jogs are dropped first. */
  emergencyStop(): boolean {
    this.coalescer.cancelAll();
    this.store.commandedPwm.fill(NaN);
    return this.publish(EMERGENCY_STOP);
  }

  private ping(): void {
    if (this.store.connection !== 'connected' || !this.client) return;
    const seq = this.store.ping.send(now());
    this.publish(encodePing(seq), false);
  }

  stop(): void {
    clearInterval(this.pingTimer);
    this.coalescer.cancelAll();
    this.client?.end(true);
    this.client = null;
    this.store.connection = 'idle';
  }
}
