/**
 * One Foxglove client's way back to the arms, under its own MQTT identity (its log-in; in the
 * anonymous demo a `foxglove-N` name of its own): it sends on `arm/{id}/control/{user}` and
 * `arm/{id}/claim/{user}` as the HUD does, so the controller core decides everything (lease,
 * limits, floor, zones; a stop passes from anyone who may publish it). A viewer has no way back:
 * its publish and service calls are refused here, before any MQTT. The MQTT connection opens on
 * the first command, so a client that only watches costs none.
 */
import type { MqttClient } from 'mqtt';
import type { Principal } from '@armtwin/auth';
import { encodeStop, userTopic, type Clock, type HolderRecord } from '@armtwin/protocol';
import { ClaimKeeper, FrameStreamer } from '@armtwin/ros2';
import type { TimedFrame } from '@armtwin/motion';

/**
 * Connects an MQTT client as `who`: in `armtwin up` in-process, with that principal; in the
 * middleware to the broker with the user's own name and the password it logged in with (null:
 * no log-in, the anonymous local demo).
 */
export type ConnectAs = (who: Principal, password: string | null) => MqttClient;

export class Session {
  private mqtt: MqttClient | undefined;
  private readonly claims = new Map<string, ClaimKeeper>();
  private readonly streams = new Map<string, FrameStreamer>();

  constructor(
    readonly who: Principal,
    private readonly password: string | null,
    private readonly connectAs: ConnectAs,
    private readonly clock: Clock,
  ) {}

  /** Why this client may not command an arm (null: it may). */
  get refusal(): string | null {
    return this.who.role === 'viewer' ? `${this.who.name} is a viewer: viewers only watch` : null;
  }

  /** Sends the e-stop of every servo (`#255PDST!`) to `armId`; ends a trajectory under way. */
  stop(armId: string): void {
    this.streams.get(armId)?.cancel();
    this.send(armId, encodeStop(255));
  }

  /** Asks for `armId` (`take`); the controller answers on the holder record. */
  take(armId: string): void {
    this.keeper(armId);
    this.client().publish(userTopic(armId, 'claim', this.who.name), 'take', { qos: 1 });
  }

  release(armId: string): void {
    this.streams.get(armId)?.cancel();
    this.claims.get(armId)?.release();
  }

  /** Plays timed frames on `armId` (a new run replaces the one under way). */
  play(armId: string, frames: readonly TimedFrame[]): void {
    let s = this.streams.get(armId);
    if (!s)
      this.streams.set(armId, (s = new FrameStreamer(this.clock, (f) => this.send(armId, f))));
    s.play(frames);
  }

  /** A new holder record of `armId`: beat while this user holds it, stop playing when another does. */
  onHolder(armId: string, record: HolderRecord): void {
    this.claims.get(armId)?.onHolder(record);
    if (record.user !== null && record.user !== this.who.name) this.streams.get(armId)?.cancel();
  }

  async close(): Promise<void> {
    for (const s of this.streams.values()) s.cancel();
    for (const k of this.claims.values()) k.release();
    await this.mqtt?.endAsync().catch(() => {});
  }

  private keeper(armId: string): ClaimKeeper {
    let k = this.claims.get(armId);
    if (!k) {
      k = new ClaimKeeper(this.who.name, false, this.clock, (payload) =>
        this.client().publish(userTopic(armId, 'claim', this.who.name), payload, { qos: 1 }),
      );
      this.claims.set(armId, k);
    }
    return k;
  }

  private send(armId: string, frames: string): void {
    this.client().publish(userTopic(armId, 'control', this.who.name), frames, { qos: 1 });
  }

  private client(): MqttClient {
    return (this.mqtt ??= this.connectAs(this.who, this.password));
  }
}
