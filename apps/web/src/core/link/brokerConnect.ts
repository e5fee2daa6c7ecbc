/**
 * The page's MQTT client factory (both of its clients: the arm link and the fleet link): the
 * connection settings' broker list (comma-separated, the first preferred) followed by
 * `@armtwin/link`, the same client wrapper the Node parts use: one mqtt.js client that moves to
 * the next broker when its own is lost and back to the first when that answers again
 * (docs/protocol.md § Several brokers). What it uses is on the client (`brokers.choice`).
 * Claims and moves perish with their connection (`perishesWithConnection`): one the broker had
 * not acknowledged when it dropped is never sent on the next; an e-stop is.
 */
import mqtt, { type IClientOptions } from 'mqtt';
import { connectBrokers } from '@armtwin/link';
import { parseBrokerList } from '@armtwin/link';
import { perishesWithConnection } from '@armtwin/protocol';
import type { ConnectOptions } from './connectOptions.ts';
import type { MqttLike } from './MqttLike.ts';

/** What both of the page's links use of the client (the fleet link also unsubscribes). */
export type PageMqtt = MqttLike & {
  unsubscribe(topics: string[], cb?: (err?: Error) => void): unknown;
};

export function brokerConnect(url: string, opts: ConnectOptions): PageMqtt {
  return connectBrokers(parseBrokerList(url, true), opts as IClientOptions, {
    connect: (u, o) => mqtt.connect(u, o),
    perishable: perishesWithConnection,
  }) as unknown as PageMqtt;
}
