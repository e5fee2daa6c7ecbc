/**
 * Messages that perish with their connection (docs/protocol.md § Several brokers): a QoS 1
 * publish the caller marks perishable is sent on the connection it was made on, or never.
 *
 * mqtt.js keeps every QoS 1 publish that the broker has not acknowledged (PUBACK) in its outgoing
 * store and sends it again at the next connect, clean session or not, and stores a publish made
 * while disconnected to send it at the next connect. For a claim (`take`, `beat`) or a move that
 * is wrong: the page's `take` would reach the arm's next broker seconds later, after the arm had
 * timed the page out, and take control again without a click. So, for a perishable message:
 * - made while disconnected: not published; its callback is told `NOT_CONNECTED`;
 * - sent and not acknowledged when the connection closes: removed from mqtt.js's store
 *   (`removeOutgoingMessage`, mqtt.js's public API); its callback is told `Message removed`.
 * What the connection had acknowledged reached that broker; the rest is for the caller to send
 * again, knowingly. Other messages (an e-stop, the status stream) keep mqtt.js's behaviour.
 * Bookkeeping from mqtt.js's `packetsend` and `packetreceive` events (their message ids).
 */
import type { MqttClient } from 'mqtt';
import type { Publish } from './republish.ts';

/** Says whether a message perishes with its connection. */
export type Perishable = (topic: string, payload: string | Uint8Array) => boolean;

/** The error a perishable publish made while disconnected gets. */
export const NOT_CONNECTED = 'not sent: not connected (a claim or a move is never sent late)';

/** Perishable publishes sent on the current connection and not acknowledged: id → topic. */
export class PerishableInFlight {
  private readonly sentOn = new Map<number, string>();
  sent(messageId: number, topic: string): void {
    this.sentOn.set(messageId, topic);
  }
  acknowledged(messageId: number): void {
    this.sentOn.delete(messageId);
  }
  /** The connection closed: what to drop, [id, topic] (and nothing is left). */
  closed(): [number, string][] {
    const dropped = [...this.sentOn];
    this.sentOn.clear();
    return dropped;
  }
}

export function dropPerishableOnClose(
  client: MqttClient,
  perishable: Perishable,
  onDrop: (topic: string) => void = () => {},
): void {
  const inFlight = new PerishableInFlight();
  client.on('packetsend', (p) => {
    if (p.cmd !== 'publish' || !p.qos || !p.messageId) return;
    if (!perishable(p.topic, p.payload as string | Uint8Array)) return;
    inFlight.sent(p.messageId, p.topic);
  });
  client.on('packetreceive', (p) => {
    if (p.cmd === 'puback' && p.messageId) inFlight.acknowledged(p.messageId);
  });
  client.on('close', () => {
    for (const [id, topic] of inFlight.closed()) {
      onDrop(topic);
      client.removeOutgoingMessage(id);
    }
  });
  const publish = client.publish.bind(client) as Publish;
  const wrapped: Publish = (topic, message, opts, callback) => {
    const cb = typeof opts === 'function' ? opts : callback;
    const qos = typeof opts === 'object' ? opts.qos : 0;
    if (qos && !client.connected && perishable(topic, message)) {
      onDrop(topic);
      cb?.(new Error(NOT_CONNECTED));
      return client;
    }
    return publish(topic, message, opts, callback);
  };
  (client as { publish: Publish }).publish = wrapped;
}
