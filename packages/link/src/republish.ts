/**
 * A QoS 1 or 2 publish that mqtt.js drops on a lost connection is published again.
 *
 * mqtt.js 5 (up to 5.16.0, mqttjs/MQTT.js#2015) loses such messages in one case. At every
 * connect it sends again, one at a time, what its outgoing store holds (not yet acknowledged).
 * Publishes made meanwhile wait in a queue beside the store (`_storeProcessingQueue`). If the
 * connection closes before the store is sent, that queue is flushed: each waiting publish's
 * callback gets `Connection closed`, and the message is gone. It is never stored, so never sent.
 * Publishes made while disconnected, and those sent but not acknowledged, go to the store and
 * survive.
 *
 * A NATS cluster whose stream leader is lost meets exactly this (docs/cluster.md § Found on the
 * cluster). The node an arm moves to takes the first re-sent message and waits 5 s for
 * JetStream to store it, then closes the connection. The 250 reports the arm made in those 5 s
 * (50 Hz) sat in the queue and were lost.
 *
 * Here every such message is published again, in order, once the close is over. The client is
 * then disconnected, so mqtt.js puts it in its outgoing store, and it is sent after the next
 * connect, as any publish made while offline. The caller's callback is told only the final
 * outcome. A client that is ending (`end()`) does not publish again, nor is a message that
 * perishes with its connection (`./perishable.ts`: a claim, a move).
 */
import type { IClientPublishOptions, MqttClient, PacketCallback } from 'mqtt';
import type { Perishable } from './perishable.ts';

/** The error mqtt.js gives a publish it dropped from its queue when a connection closed. */
const DROPPED = 'Connection closed';

/** mqtt.js's `publish`, as a wrapper replaces it. */
export type Publish = (
  topic: string,
  message: string | Buffer,
  opts?: IClientPublishOptions | PacketCallback,
  callback?: PacketCallback,
) => MqttClient;

export function republishDroppedPublishes(
  client: MqttClient,
  onRepublish: (topic: string) => void = () => {},
  perishable: Perishable = () => false,
): void {
  const publish = client.publish.bind(client) as Publish;
  const wrapped: Publish = (topic, message, opts, callback) => {
    if (typeof opts === 'function') return publish(topic, message, opts);
    if (!opts?.qos) return publish(topic, message, opts, callback);
    const settle: PacketCallback = (err, packet) => {
      if (
        err?.message === DROPPED &&
        !client.disconnecting &&
        !client.disconnected &&
        !perishable(topic, message)
      ) {
        // After the close: mqtt.js flushes the queue while its own close handling is under way.
        queueMicrotask(() => {
          onRepublish(topic);
          publish(topic, message, opts, settle);
        });
        return;
      }
      callback?.(err, packet);
    };
    return publish(topic, message, opts, settle);
  };
  (client as { publish: Publish }).publish = wrapped;
}
