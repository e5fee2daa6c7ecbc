/**
 * A subscription the broker refused (a SUBACK failure code, 0x80 set) is asked for again, every
 * `retryMs` while the connection it was refused on lasts, until the broker grants it. The part's
 * callback is told the first answer, as mqtt.js tells it; the retries are silent but for
 * `onRetry`. A new connection ends the retries of the old one: every part subscribes again on
 * connect.
 *
 * Why: a NATS cluster refuses a QoS 1 subscription while JetStream elects new leaders after a node
 * is lost (docs/cluster.md), which is exactly when the parts of that node arrive on another. An
 * arm whose control subscription was refused then would be deaf to every command, the stop
 * included. Used by `connectBrokers` for a broker list; one broker behaves as before.
 */
import type { IClientSubscribeOptions, MqttClient } from 'mqtt';

/** `subscribe`'s callback, as mqtt.js calls it: the error, the subscriptions, the SUBACK. */
type SubscribeCallback = (
  err: Error | null,
  granted?: { topic: string; qos: number }[],
  packet?: { granted?: (number | object)[] },
) => void;

export function retryRefusedSubscriptions(
  client: MqttClient,
  retryMs: number,
  onRetry: (topics: string[]) => void = () => {},
): void {
  let connection = 0;
  client.on('close', () => connection++);
  const subscribe = client.subscribe.bind(client) as (
    topic: string | string[],
    opts: IClientSubscribeOptions,
    cb: SubscribeCallback,
  ) => MqttClient;
  const ask = (
    topics: string[],
    opts: IClientSubscribeOptions,
    cb: SubscribeCallback | null,
    asMap?: Record<string, { qos?: number } | boolean>,
  ) => {
    const qosOf = (t: string) => {
      const o = asMap?.[t];
      return typeof o === 'object' ? (o.qos as IClientSubscribeOptions['qos']) : undefined;
    };
    const on = connection;
    const answer: SubscribeCallback = (err, subs, packet) => {
      cb?.(err, subs, packet);
      const refused = topics.filter((_, i) => {
        const code = packet?.granted?.[i];
        return typeof code === 'number' && (code & 0x80) !== 0;
      });
      if (!err || refused.length === 0) return;
      const timer = setTimeout(() => {
        if (connection !== on || !client.connected || client.disconnecting) return;
        onRetry(refused);
        // Each filter at the QoS it was asked for (a resubscription mixes them).
        const byQos = new Map<IClientSubscribeOptions['qos'], string[]>();
        for (const t of refused) {
          const qos = qosOf(t) ?? opts.qos;
          byQos.set(qos, [...(byQos.get(qos) ?? []), t]);
        }
        for (const [qos, group] of byQos) ask(group, { ...opts, qos }, null);
      }, retryMs);
      (timer as { unref?: () => void }).unref?.();
    };
    if (asMap) (subscribe as unknown as (m: object, c: SubscribeCallback) => void)(asMap, answer);
    else subscribe(topics, opts, answer);
  };
  // The forms the parts use (a filter or a list, options, a callback), and mqtt.js's own
  // resubscription after a reconnect (a map of filter → options, `resubscribe: true`).
  const original = client.subscribe.bind(client) as (...a: unknown[]) => MqttClient;
  client.subscribe = ((topic: unknown, opts?: unknown, cb?: unknown) => {
    const callback = (typeof opts === 'function' ? opts : cb) as SubscribeCallback | undefined;
    if (
      typeof topic === 'string' ||
      (Array.isArray(topic) && topic.every((t) => typeof t === 'string'))
    ) {
      const options = (
        typeof opts === 'object' && opts ? opts : { qos: 0 }
      ) as IClientSubscribeOptions;
      ask(typeof topic === 'string' ? [topic] : (topic as string[]), options, callback ?? null);
      return client;
    }
    const map = topic as Record<string, { qos?: number } | boolean> | null;
    const filters = map ? Object.keys(map).filter((k) => k !== 'resubscribe') : [];
    const first = filters.length ? map![filters[0]!] : undefined;
    if (!map?.resubscribe || typeof first !== 'object') return original(topic, opts, cb);
    ask(
      filters,
      { qos: (first.qos ?? 0) as IClientSubscribeOptions['qos'] },
      callback ?? null,
      map,
    );
    return client;
  }) as MqttClient['subscribe'];
}
