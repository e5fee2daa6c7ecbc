/**
 * The middleware's intake from a NATS cluster (`NATS_URL`, docs/cluster.md), in place of its MQTT
 * subscriptions. Arms and pages speak MQTT to the cluster's nodes; NATS's MQTT support stores every
 * QoS 1 message in the JetStream stream `$MQTT_msgs` (replicated on the cluster's nodes) before
 * it acknowledges it to the publisher. Every middleware reads that stream through ONE durable
 * pull consumer (`NATS_CONSUMER`, filtered to the topics the middleware stores), so each message
 * goes to one middleware: several share the stream, none reads it twice.
 *
 * A message is acknowledged only after its points are in the spool's journal (as over MQTT). One
 * not acknowledged within `ackWaitMs` (its middleware died, or the node its acknowledgement went
 * through) is delivered again, to any of them: its points carry the arm's `$TIM`, so the second
 * write overwrites the first with the same values (README, Unique timestamps): stored once.
 *
 * It has the MQTT edge's shape (`MqttEdge`), so the rest of the middleware does not know which it
 * has: "the broker in use" is the NATS server the client is connected to. Nothing is published.
 */
import { connect, type NatsConnection } from '@nats-io/transport-node';
import {
  AckPolicy,
  DeliverPolicy,
  jetstream,
  jetstreamManager,
  type ConsumerConfig,
  type ConsumerMessages,
} from '@nats-io/jetstream';
import type { BrokerChoice } from '@armtwin/link';
import type { MqttEdge, MqttHandlers } from './mqtt.ts';
import { subscriptionTopics } from './mqtt.ts';
import {
  MQTT_MSGS_PREFIX,
  MQTT_MSGS_STREAM,
  subjectToTopic,
  topicToSubject,
} from './nats-subjects.ts';

export interface NatsIntakeOptions {
  /** The cluster's servers, comma-separated (`nats://host:4222,…`). */
  url: string;
  /** The durable consumer every middleware shares. */
  consumer: string;
  /** This instance's connection name (its MQTT client id). */
  name: string;
  username: string;
  password: string;
  reconnectMs: number;
  /** A message not acknowledged for this long is delivered again. */
  ackWaitMs: number;
  /** Told what happens to the consumer (made, bound, its reading broken off). */
  note?: (message: string, fields: object) => void;
}

/** Unacknowledged messages the consumer lets out to all its middlewares together. */
const MAX_ACK_PENDING = 10_000;
/** Messages a middleware asks for at a time. */
const PULL_BATCH = 256;

/** The durable consumer: what the middleware stores, from the cluster's MQTT message stream. */
export function consumerConfig(
  o: Pick<NatsIntakeOptions, 'consumer' | 'ackWaitMs'>,
): Partial<ConsumerConfig> {
  return {
    durable_name: o.consumer,
    ack_policy: AckPolicy.Explicit,
    // From when the consumer was first made; it is durable (replicated as the stream is) after.
    deliver_policy: DeliverPolicy.New,
    filter_subjects: subscriptionTopics('').map((t) => MQTT_MSGS_PREFIX + topicToSubject(t)),
    ack_wait: o.ackWaitMs * 1_000_000,
    max_ack_pending: MAX_ACK_PENDING,
  };
}

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

export function startNatsIntake(o: NatsIntakeOptions, h: MqttHandlers): MqttEdge {
  const servers = o.url.split(',');
  const hostOf = (u: string) => new URL(u).host;
  const choice = (server: string): BrokerChoice => {
    const i = Math.max(
      0,
      servers.findIndex((u) => hostOf(u) === server),
    );
    return { index: i, count: servers.length, url: servers[i]! };
  };
  let nc: NatsConnection | null = null;
  let messages: ConsumerMessages | null = null;
  let stopping = false;
  let current: BrokerChoice | null = null;
  let used: BrokerChoice | null = null;

  const connected = (server: string) => {
    current = choice(server);
    if (!used || used.index !== current.index)
      h.onMove({ from: used, to: current, reason: used ? 'lost' : 'start' });
    used = current;
    h.onConnect();
  };

  const watch = async (conn: NatsConnection) => {
    for await (const s of conn.status()) {
      if (s.type === 'disconnect') {
        current = null;
        h.onClose();
      } else if (s.type === 'reconnect') connected(s.server);
      else if (s.type === 'error') h.onError(new Error(String(s.error)));
    }
  };

  /** Makes the consumer, or updates it when it exists with another configuration. */
  const ensureConsumer = async (conn: NatsConnection) => {
    const jsm = await jetstreamManager(conn);
    const config = consumerConfig(o);
    try {
      const info = await jsm.consumers.add(MQTT_MSGS_STREAM, config);
      o.note?.('NATS: the shared consumer is there', {
        consumer: o.consumer,
        delivered: info.delivered.stream_seq,
        pending: info.num_pending,
      });
    } catch (err) {
      if (!/already exists/i.test((err as Error).message)) throw err;
      const { durable_name: _, ...change } = config;
      await jsm.consumers.update(MQTT_MSGS_STREAM, o.consumer, change);
      o.note?.('NATS: the shared consumer is there (its settings updated)', {
        consumer: o.consumer,
      });
    }
  };

  const consume = async (conn: NatsConnection) => {
    const consumer = await jetstream(conn).consumers.get(MQTT_MSGS_STREAM, o.consumer);
    messages = await consumer.consume({ max_messages: PULL_BATCH });
    for await (const m of messages) {
      const topic = subjectToTopic(m.subject.slice(MQTT_MSGS_PREFIX.length));
      h.onMessage(topic, Buffer.from(m.data.buffer, m.data.byteOffset, m.data.byteLength));
      h.commit();
      // Durable in the journal now; while the spool is full, wait (the stream keeps the rest).
      const wait = h.gate();
      if (wait) await wait.catch(() => {});
      m.ack();
    }
  };

  void (async () => {
    while (!stopping && !nc) {
      try {
        nc = await connect({
          servers,
          name: o.name,
          ...(o.username ? { user: o.username, pass: o.password } : {}),
          noRandomize: true, // the list's order, as MQTT_URL's: the first is preferred
          maxReconnectAttempts: -1,
          reconnectTimeWait: o.reconnectMs,
        });
      } catch (err) {
        h.onError(err as Error);
        await sleep(o.reconnectMs);
      }
    }
    if (!nc) return;
    if (stopping) return void (await nc.close());
    void watch(nc);
    connected(nc.getServer());
    // The stream is made by the first MQTT client of the account; the consumer may be lost
    // with a node. Until it is there, and after anything breaks the loop, try again.
    while (!stopping && !nc.isClosed()) {
      try {
        await ensureConsumer(nc);
        await consume(nc);
        o.note?.('NATS: reading the shared consumer ended', {});
      } catch (err) {
        if (!stopping) h.onError(err as Error);
        o.note?.('NATS: reading the shared consumer broke off', { err: (err as Error).message });
      }
      if (!stopping) await sleep(o.reconnectMs);
    }
  })();

  return {
    brokers: {
      get choice() {
        return current ?? used ?? choice('');
      },
    },
    publish: () => {
      throw new Error('the NATS intake publishes nothing');
    },
    async settle(timeoutMs) {
      // Unacknowledged messages are delivered again: nothing to wait for but the acks sent.
      await Promise.race([nc?.flush().catch(() => {}), sleep(timeoutMs)]);
    },
    end(_force, _opts, cb) {
      stopping = true;
      void (async () => {
        await messages?.close().catch(() => {});
        await nc?.drain().catch(() => {});
        cb();
      })();
    },
  };
}
