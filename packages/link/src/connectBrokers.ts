/**
 * An mqtt.js client over an ordered list of brokers (docs/protocol.md § Several brokers), the
 * same in Node and in the page. It is ONE MqttClient: its handlers, its subscriptions and its
 * offline queue (QoS 1 messages published while disconnected, those not yet acknowledged, and
 * those mqtt.js would drop when a connection closes while it re-sends them: `./republish.ts`)
 * survive a move (except those that perish with their connection: `./perishable.ts`), because only the stream under it changes: at every (re)connect mqtt.js asks
 * the stream builder for a stream, and the builder asks the policy (`BrokerFailover`,
 * `./brokers.ts`) which broker that is. Each broker's own builder is mqtt.js's, made by
 * `connect(url, { manualConnect: true })`, so every scheme mqtt.js knows (mqtt, mqtts, ws, wss)
 * works as it does with one broker.
 *
 * While on a fall-back, the first broker is probed every `probeMs` by a client of its own; once
 * it has answered `returnAfterProbes` probes in a row the stream is dropped (so the broker
 * publishes the part's last will there, as for a lost link) and the next connection goes to the
 * first. mqtt.js's own `servers` option cycles through a list but never returns to the first
 * and never probes, hence this.
 */
import mqtt, { type IClientOptions, type MqttClient } from 'mqtt';
import {
  BrokerFailover,
  DEFAULT_BROKER_LIST_OPTIONS,
  type BrokerListOptions,
  type BrokerMove,
} from './brokers.ts';
import { probeBroker, type ConnectFn, type ProbeConnected } from './probe.ts';
import { dropPerishableOnClose, type Perishable } from './perishable.ts';
import { republishDroppedPublishes } from './republish.ts';
import { retryRefusedSubscriptions } from './resubscribe.ts';

export interface BrokerLinkOptions extends BrokerListOptions {
  /** Makes an mqtt.js client (tests and the page may hand in theirs). */
  connect: ConnectFn;
  /** Told of the first connection and of every move to another broker. */
  onMove: (move: BrokerMove) => void;
  /**
   * A probe connects with the link's options, these on top, no last will and no retry
   * (default: its own client id, a clean session).
   */
  probeOptions: Partial<IClientOptions>;
  /** Runs on a probe's connection before it ends (a part may register its session there). */
  onProbeConnected?: ProbeConnected;
  /**
   * The QoS 1 messages sent on the connection they were made on or never (`./perishable.ts`):
   * not queued while disconnected, dropped if unacknowledged when it closes (default: none).
   */
  perishable?: Perishable;
}

export const DEFAULT_BROKER_LINK_OPTIONS: Omit<BrokerLinkOptions, 'probeOptions'> = {
  ...DEFAULT_BROKER_LIST_OPTIONS,
  connect: (url, opts) => mqtt.connect(url, opts),
  onMove: () => {},
};

/** The client, with the policy that says which broker it uses. */
export type BrokerClient = MqttClient & { brokers: BrokerFailover };

type StreamBuilder = (client: MqttClient) => unknown;
/** mqtt.js keeps the stream builder in a field its typings call private. */
const builder = (c: MqttClient) => c as unknown as { streamBuilder: StreamBuilder };

export function connectBrokers(
  urls: readonly string[],
  opts: IClientOptions,
  options: Partial<BrokerLinkOptions> = {},
): BrokerClient {
  const o = { ...DEFAULT_BROKER_LINK_OPTIONS, ...options };
  const failover = new BrokerFailover(urls, o);
  const several = urls.length > 1;
  // One broker: the client mqtt.js makes, as it makes it. Several: made unconnected, its stream
  // builder replaced, then connected.
  const client = o.connect(
    urls[0]!,
    several ? { ...opts, manualConnect: true } : opts,
  ) as BrokerClient;
  client.brokers = failover;
  // mqtt.js drops QoS 1 publishes made while it re-sends its store, if the connection closes then.
  republishDroppedPublishes(client, undefined, o.perishable);
  if (o.perishable) dropPerishableOnClose(client, o.perishable);
  if (several) {
    const builders = urls.map((url, i) =>
      i === 0
        ? builder(client).streamBuilder
        : builder(o.connect(url, { ...opts, manualConnect: true })).streamBuilder,
    );
    builder(client).streamBuilder = (c) => builders[failover.choice.index]!(c);
    // A broker of a cluster may refuse a subscription while it recovers from a lost node.
    retryRefusedSubscriptions(client, opts.reconnectPeriod ?? 1000);
  }
  client.on('connect', () => {
    const move = failover.connected();
    if (move) o.onMove(move);
  });
  client.on('close', () => failover.closed());

  if (several) {
    const probeOpts: IClientOptions = {
      ...opts,
      clientId: `${opts.clientId ?? 'armtwin'}-probe`,
      clean: true,
      ...o.probeOptions,
    };
    let inFlight = false;
    const probe = () => {
      if (!failover.probing || inFlight || client.disconnecting) return;
      inFlight = true;
      void probeBroker(
        o.connect,
        urls[0]!,
        probeOpts,
        Math.min(o.probeMs, opts.connectTimeout ?? o.probeMs),
        o.onProbeConnected,
      ).then((ok) => {
        inFlight = false;
        if (failover.probed(ok) && client.connected && !client.disconnecting)
          (client.stream as { destroy(): void }).destroy();
      });
    };
    const timer = setInterval(probe, o.probeMs);
    (timer as { unref?: () => void }).unref?.(); // the probes alone keep no process alive
    client.on('end', () => clearInterval(timer));
    client.connect();
  }
  return client;
}
