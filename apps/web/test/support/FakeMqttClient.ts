/**
 * A fake mqtt.js client for unit tests of the page's links (../../src/core/link/MqttLike.ts): it
 * records the handlers the link registers (a test fires them with `emit`), every publish, and
 * how it was ended. A unit test only; tests of the real thing use a real broker.
 */
import type { MqttLike } from '../../src/core/link/MqttLike.ts';

export interface Published {
  topic: string;
  payload: string;
  qos: 0 | 1;
  retain: boolean;
}

export class FakeMqttClient implements MqttLike {
  readonly handlers = new Map<string, ((...args: never[]) => void)[]>();
  readonly published: Published[] = [];
  /** Every topic subscribed, in order (a test may clear it). */
  subscribed: string[] = [];
  /** Every topic unsubscribed, in order. */
  readonly unsubscribed: string[] = [];
  /** `end`'s `force` (false for a clean DISCONNECT), null until ended. */
  ended: boolean | null = null;

  on(event: string, cb: (...args: never[]) => void) {
    this.handlers.set(event, [...(this.handlers.get(event) ?? []), cb]);
    return this;
  }
  /** Fires the handlers registered for `event` (`connect`, `message`, …). */
  emit(event: string, ...args: unknown[]) {
    for (const cb of this.handlers.get(event) ?? []) (cb as (...a: unknown[]) => void)(...args);
  }
  subscribe(topics: string[]) {
    this.subscribed.push(...topics);
    return this;
  }
  unsubscribe(topics: string[]) {
    this.unsubscribed.push(...topics);
    return this;
  }
  publish(topic: string, payload: string, opts?: { qos: 0 | 1; retain?: boolean }) {
    this.published.push({ topic, payload, qos: opts?.qos ?? 0, retain: opts?.retain ?? false });
    return this;
  }
  end(force?: boolean) {
    this.ended = force ?? false;
    return this;
  }
}
