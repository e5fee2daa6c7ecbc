/**
 * The MQTT edge (mqtt.js v5, protocol 3.1.1): a persistent session (`clean: false`, fixed
 * client id) subscribed to every arm's status and control topics (the plain `arm/+/control` and
 * the per-user `arm/+/control/+`, docs/protocol.md § Control) at the configured QoS,
 * optionally through a shared subscription `$share/<group>/…`.
 *
 * mqtt.js emits 'message' and only then calls `handleMessage(packet, done)`; the PUBACK of a
 * QoS 1 message is sent when `done` runs, and the next packet is not processed before. The
 * middleware's 'message' listener puts the points on disk synchronously, so a message is
 * acknowledged only once it is durable. While the spool is full `done` waits: intake pauses
 * and the broker keeps the messages queued in the session.
 */
import { connect, type IClientOptions, type MqttClient } from 'mqtt';
import { allArmsTopic, linkOptions } from '@armtwin/protocol';

export interface MqttOptions {
  url: string;
  username: string;
  password: string;
  clientId: string;
  qos: 0 | 1;
  keepaliveS: number;
  reconnectMs: number;
  /** '' = plain subscriptions; else `$share/<group>/…`. */
  shareGroup: string;
}

/** The topic filters subscribed to. */
export function subscriptionTopics(shareGroup: string): string[] {
  const plain = [
    allArmsTopic('status'),
    allArmsTopic('control'),
    `${allArmsTopic('control')}/+`,
    'arm/+/audit', // control events (docs/protocol.md § Control), stored as `audit`
  ];
  return shareGroup ? plain.map((t) => `$share/${shareGroup}/${t}`) : plain;
}

export interface MqttHandlers {
  onMessage(topic: string, payload: Buffer): void;
  onConnect(): void;
  onClose(): void;
  onError(err: Error): void;
  /** Resolves when intake may go on (immediately unless the spool is full). */
  gate(): Promise<void> | null;
}

export type ConnectFn = (url: string, opts: IClientOptions) => MqttClient;

export function startMqtt(
  o: MqttOptions,
  h: MqttHandlers,
  connectFn: ConnectFn = connect,
): MqttClient {
  const client = connectFn(o.url, {
    clientId: o.clientId,
    clean: false,
    ...linkOptions({ keepalive: o.keepaliveS, reconnectPeriod: o.reconnectMs }),
    protocolVersion: 4,
    ...(o.username ? { username: o.username, password: o.password } : {}),
  });
  const topics = subscriptionTopics(o.shareGroup);
  client.handleMessage = (_packet, done) => {
    const wait = h.gate();
    if (wait)
      void wait.then(
        () => done(),
        () => done(),
      );
    else done();
  };
  client.on('message', (topic, payload) => h.onMessage(topic, payload));
  client.on('connect', () => {
    // PUBACKs are small: don't let Nagle's algorithm hold them back (~40 ms otherwise).
    (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true);
    h.onConnect();
    client.subscribe(topics, { qos: o.qos }, (err) => {
      if (err) h.onError(err);
    });
  });
  client.on('close', () => h.onClose());
  client.on('error', (err) => h.onError(err));
  return client;
}
