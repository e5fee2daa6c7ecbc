/**
 * Connection defaults every part shares (PROTOCOL.md §6: "MQTT: keep-alive 60 s, reconnect
 * every 1000 ms"), declared once and imported by the HUD, the simulator, the gateway, the
 * middleware and the broker. Each part may override them through its own options.
 */

/** Largest MQTT payload any part accepts or sends, bytes (brokers: `max_packet_size`). */
export const MAX_PAYLOAD_BYTES = 65_536;
/** MQTT keep-alive, seconds. */
export const MQTT_KEEPALIVE_S = 60;
/** Delay between MQTT reconnect attempts, ms. */
export const MQTT_RECONNECT_MS = 1000;
/** How long one MQTT connect attempt may take, ms. */
export const MQTT_CONNECT_TIMEOUT_MS = 10_000;

/**
 * QoS of the subscriptions of every part that connects with a clean session: 0. The arms (the
 * sim's, the gateway's and the motion service's control, claim, operator, request and fault
 * topics) and the page (its arm's status, holder and audit, the fleet's topics, the model copy's,
 * the cameras'). With a clean session a broker keeps nothing for the client across a reconnect,
 * so QoS 1 delivers nothing more than QoS 0 over a live connection (either may repeat a message,
 * QoS 1 being at least once), and a retained message still comes at subscribe. What QoS 1 costs
 * is large on a NATS cluster: there each QoS 1 subscription is a JetStream consumer replicated on
 * every node, remade slowly after a lost node, and a message reaches it only once stored; a QoS 0
 * subscription is a plain NATS subscription, reached before the store (docs/cluster.md).
 * Publishers keep their QoS (a QoS 1 publish is still acknowledged); the middleware, whose
 * session persists so that a broker keeps its messages while it is away, subscribes at QoS 1.
 */
export const CLEAN_SESSION_SUBSCRIBE_QOS = 0;

/** The shared part of every armtwin MQTT client's connect options (mqtt.js names). */
export interface LinkOptions {
  keepalive: number;
  reconnectPeriod: number;
  connectTimeout: number;
}

/** The defaults above as mqtt.js options, with `overrides` on top. */
export const linkOptions = (overrides: Partial<LinkOptions> = {}): LinkOptions => ({
  keepalive: MQTT_KEEPALIVE_S,
  reconnectPeriod: MQTT_RECONNECT_MS,
  connectTimeout: MQTT_CONNECT_TIMEOUT_MS,
  ...overrides,
});
