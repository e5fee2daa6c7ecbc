/**
 * The MQTT edge (mqtt.js v5, protocol 3.1.1): a persistent session (`clean: false`, fixed
 * client id) subscribed to every arm's status and control topics (the plain `arm/+/control` and
 * the per-user `arm/+/control/+`, docs/protocol.md § Control) at the configured QoS,
 * optionally through a shared subscription `$share/<group>/…`.
 *
 * mqtt.js emits 'message' and only then calls `handleMessage(packet, done)`; the PUBACK of a
 * QoS 1 message is written when `done` runs, and the next packet is handled after it (on the
 * next tick). The middleware's 'message' listener takes the points into memory (`onMessage`);
 * they reach the journal in one write per event-loop turn (`commit`, at setImmediate, after
 * every packet the turn's socket reads brought). So that a message is still acknowledged only
 * once it is durable, the connection's socket is corked from the first QoS 1 message of a turn
 * until that commit: the PUBACKs leave after the write, in one segment. (A transport without
 * cork commits before each acknowledgement, one write per message as before.) While the spool
 * is full `done` waits: intake pauses and the broker keeps the messages queued in the session.
 *
 * Several brokers (`url` a comma-separated list, docs/protocol.md § Several brokers): the
 * middleware does not move from broker to broker as the publishers do; it keeps a connection,
 * with the same persistent session and subscriptions, to EVERY broker of its list, each with its
 * own reconnect, and takes in what arrives on any of them. So whichever broker a publisher is on,
 * the middleware is subscribed there already, whatever the order in which parts move, and what
 * a broker queued for it while that connection was down comes when it is back. "The broker in
 * use" (logs, metrics, /healthz, what the middleware publishes) is the first of the list that is
 * connected; a change of it is logged as a move.
 */
import { connect, type IClientOptions, type IClientPublishOptions, type MqttClient } from 'mqtt';
import { allArmsTopic, linkOptions } from '@armtwin/protocol';
import { parseBrokerList, type BrokerChoice, type BrokerMove } from '@armtwin/link';

export interface MqttOptions {
  /** One broker URL, or an ordered comma-separated list. */
  url: string;
  username: string;
  password: string;
  clientId: string;
  qos: 0 | 1;
  keepaliveS: number;
  reconnectMs: number;
  /** '' = plain subscriptions; else `$share/<group>/…`. */
  shareGroup: string;
  /** Filters subscribed to as they are, never shared (the camera announcements, to record them). */
  extraTopics?: readonly string[];
}

/** The topic filters subscribed to. */
export function subscriptionTopics(shareGroup: string): string[] {
  const plain = [
    allArmsTopic('status'),
    allArmsTopic('control'),
    `${allArmsTopic('control')}/+`,
    'arm/+/audit', // control events (docs/protocol.md § Control), stored as `audit`
    'arm/+/profile', // the robot each arm announces (retained), stored as `profile`
  ];
  return shareGroup ? plain.map((t) => `$share/${shareGroup}/${t}`) : plain;
}

export interface MqttHandlers {
  /** Takes a message in (into memory: durable at the next `commit`). */
  onMessage(topic: string, payload: Buffer): void;
  /** Makes what `onMessage` took durable; the messages' acknowledgements leave after it. */
  commit(): void;
  onConnect(): void;
  onClose(): void;
  onError(err: Error): void;
  /** The first connection, and every move to another broker. */
  onMove(move: BrokerMove): void;
  /** Resolves when intake may go on (immediately unless the spool is full). */
  gate(): Promise<void> | null;
}

/** A writable that holds its writes while corked (Node's streams, the socket under mqtt.js). */
interface Corkable {
  cork(): void;
  uncork(): void;
}

export type ConnectFn = (url: string, opts: IClientOptions) => MqttClient;

const noLog = (): void => {};

/** The middleware's MQTT client(s): one per broker of its list. */
export interface MqttEdge {
  /** The broker in use: the first of the list connected (the last one used while none is). */
  readonly brokers: { readonly choice: BrokerChoice };
  /** Publishes through the broker in use (queued by its client while it is down). */
  publish(topic: string, payload: string | Buffer, opts: IClientPublishOptions): void;
  /**
   * Resolves once every connected broker has answered a subscription to the same filters (or
   * after `timeoutMs`): a broker answers in order, so what it sent before (the last samples of
   * an arm that has just stopped) has been handled by then. Asking again changes nothing else.
   */
  settle(timeoutMs: number): Promise<void>;
  /** Ends every connection; `cb` once all have ended. */
  end(force: boolean, opts: object, cb: () => void): void;
}

export function startMqtt(
  o: MqttOptions,
  h: MqttHandlers,
  connectFn: ConnectFn = connect,
): MqttEdge {
  const urls = parseBrokerList(o.url);
  const topics = [...subscriptionTopics(o.shareGroup), ...(o.extraTopics ?? [])];
  const options: IClientOptions = {
    clientId: o.clientId,
    clean: false,
    ...linkOptions({ keepalive: o.keepaliveS, reconnectPeriod: o.reconnectMs }),
    protocolVersion: 4,
    ...(o.username ? { username: o.username, password: o.password } : {}),
    // mqtt.js logs ~10 lines a packet through `debug`, each call asking whether it is enabled;
    // unless DEBUG is set none prints, so give it a logger that does nothing at once.
    ...(process.env['DEBUG'] ? {} : { log: noLog }),
  };
  const choice = (index: number): BrokerChoice => ({
    index,
    count: urls.length,
    url: urls[index]!,
  });
  const up = urls.map(() => false);
  let current = -1; // the broker in use, -1 while none is connected
  let used = -1; // the one in use last
  // The broker in use is the first connected; say when it changes (a move) or comes or goes.
  const update = (reason: BrokerMove['reason']) => {
    const next = up.indexOf(true);
    if (next === current) return;
    current = next;
    if (next < 0) return h.onClose();
    if (next !== used)
      h.onMove({
        from: used < 0 ? null : choice(used),
        to: choice(next),
        reason: used < 0 ? 'start' : reason,
      });
    used = next;
    h.onConnect();
  };
  // One commit per event-loop turn; the sockets corked meanwhile hold that turn's PUBACKs.
  const corked = new Set<Corkable>();
  let scheduled = false;
  const commitNow = () => {
    scheduled = false;
    h.commit();
    for (const stream of corked) stream.uncork();
    corked.clear();
  };
  /** Lets mqtt.js go on (write the PUBACK, take the next packet) once the message may be acked. */
  const release = (client: MqttClient, qos: number | undefined, done: () => void) => {
    if (!scheduled) {
      scheduled = true;
      setImmediate(commitNow);
    }
    if (qos !== 0) {
      const stream = client.stream as Partial<Corkable> | undefined;
      if (stream?.cork && stream.uncork) {
        if (!corked.has(stream as Corkable)) {
          stream.cork();
          corked.add(stream as Corkable);
        }
      } else h.commit();
    }
    done();
  };
  const clients = urls.map((url, i) => {
    const client = connectFn(url, options);
    client.handleMessage = (packet, done) => {
      const wait = h.gate();
      if (!wait) return release(client, packet.qos, done); // no closure a message while open
      const go = () => release(client, packet.qos, done);
      void wait.then(go, go);
    };
    client.on('message', (topic, payload) => h.onMessage(topic, payload));
    client.on('connect', () => {
      // PUBACKs are small: don't let Nagle's algorithm hold them back (~40 ms otherwise).
      (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true);
      client.subscribe(topics, { qos: o.qos }, (err) => {
        if (err) h.onError(err);
      });
      up[i] = true;
      update('first-back');
    });
    client.on('close', () => {
      up[i] = false;
      update('lost');
    });
    client.on('error', (err) =>
      h.onError(urls.length > 1 ? new Error(`broker ${i + 1}: ${err.message}`) : err),
    );
    return client;
  });
  return {
    brokers: {
      get choice() {
        return choice(current >= 0 ? current : Math.max(used, 0));
      },
    },
    publish: (topic, payload, opts) =>
      void clients[current >= 0 ? current : Math.max(used, 0)]!.publish(topic, payload, opts),
    async settle(timeoutMs) {
      let timer: NodeJS.Timeout | undefined;
      const late = new Promise<void>((resolve) => (timer = setTimeout(resolve, timeoutMs)));
      const answered = clients
        .filter((c) => c.connected)
        .map((c) => c.subscribeAsync(topics, { qos: o.qos }).catch(() => {}));
      await Promise.race([Promise.all(answered), late]);
      clearTimeout(timer);
    },
    end(force, opts, cb) {
      let left = clients.length;
      for (const c of clients) c.end(force, opts, () => --left === 0 && cb());
    },
  };
}
