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
 *
 * Several brokers (`url` a comma-separated list, docs/protocol.md § Several brokers): the one
 * client follows the list (`@armtwin/link`), and its persistent session is registered on every
 * fall-back at start, and on the first by every probe while away from it: a probe connects with
 * this client id, `clean: false`, subscribes and leaves without acknowledging anything, so each
 * broker keeps for the middleware what is published there while it is elsewhere. It goes back to
 * the first one probe later than the publishers do, so they are back before it leaves.
 */
import { connect, type IClientOptions, type MqttClient } from 'mqtt';
import { connectBrokers, probeBroker, type BrokerClient } from '@armtwin/link';
import {
  allArmsTopic,
  DEFAULT_BROKER_LIST_OPTIONS,
  linkOptions,
  parseBrokerList,
  type BrokerMove,
} from '@armtwin/protocol';

export interface MqttOptions {
  /** One broker URL, or an ordered comma-separated list. */
  url: string;
  /** While on a fall-back, how often the first broker is probed, ms. */
  probeMs: number;
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
  /** The first connection, and every move to another broker. */
  onMove(move: BrokerMove): void;
  /** Resolves when intake may go on (immediately unless the spool is full). */
  gate(): Promise<void> | null;
}

export type ConnectFn = (url: string, opts: IClientOptions) => MqttClient;

/** The middleware goes back to the first broker one probe after the publishers do. */
export const MIDDLEWARE_RETURN_AFTER_PROBES = DEFAULT_BROKER_LIST_OPTIONS.returnAfterProbes + 1;

export function startMqtt(
  o: MqttOptions,
  h: MqttHandlers,
  connectFn: ConnectFn = connect,
): BrokerClient {
  const urls = parseBrokerList(o.url);
  const topics = subscriptionTopics(o.shareGroup);
  const options: IClientOptions = {
    clientId: o.clientId,
    clean: false,
    ...linkOptions({ keepalive: o.keepaliveS, reconnectPeriod: o.reconnectMs }),
    protocolVersion: 4,
    ...(o.username ? { username: o.username, password: o.password } : {}),
  };
  // A probe holds this client's session there: subscribed, nothing acknowledged, so what is
  // queued stays queued for the real connection.
  // A queued message arriving also says the session is there (and, as it is never
  // acknowledged, mqtt.js reads nothing after it: not even the SUBACK).
  const register = (probe: MqttClient) =>
    new Promise<void>((resolve, reject) => {
      probe.handleMessage = () => resolve();
      probe.subscribe(topics, { qos: o.qos }, (err) => (err ? reject(err) : resolve()));
    });
  const client = connectBrokers(urls, options, {
    connect: connectFn,
    probeMs: o.probeMs,
    returnAfterProbes: MIDDLEWARE_RETURN_AFTER_PROBES,
    probeOptions: { clientId: o.clientId, clean: false },
    onProbeConnected: register,
    onMove: (move) => h.onMove(move),
  });
  for (const url of urls.slice(1))
    void probeBroker(connectFn, url, options, options.connectTimeout ?? o.probeMs, register).then(
      (ok) => {
        if (!ok)
          h.onError(new Error(`fall-back broker ${url}: session not registered (unreachable)`));
      },
    );
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
