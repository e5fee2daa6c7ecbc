/**
 * The part of mqtt.js's MqttClient the page's links use, and the factory that makes one. The
 * page hands in mqtt.js (src/ui/app/createHud.ts); a unit test hands in a fake.
 */
import type { BrokerChoice } from '@armtwin/link';
import type { ConnectOptions } from './connectOptions.ts';

export interface MqttLike {
  on(event: 'connect' | 'reconnect' | 'close' | 'offline' | 'end', cb: () => void): unknown;
  on(event: 'error', cb: (err: Error) => void): unknown;
  on(event: 'message', cb: (topic: string, payload: Uint8Array) => void): unknown;
  subscribe(topics: string[], opts: { qos: 0 | 1 }, cb?: (err: Error | null) => void): unknown;
  /** Optional on a fake; mqtt.js has it (the copy's topics are let go when leaving Model mode). */
  unsubscribe?(topics: string[]): unknown;
  publish(
    topic: string,
    payload: string,
    opts: { qos: 0 | 1; retain?: boolean },
    cb?: (err?: Error) => void,
  ): unknown;
  end(force?: boolean): unknown;
  /** Which broker of the list it uses (./brokerConnect.ts); absent on a one-broker fake. */
  readonly brokers?: { readonly choice: BrokerChoice };
}

export type MqttConnect = (url: string, opts: ConnectOptions) => MqttLike;
