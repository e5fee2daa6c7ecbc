/**
 * The link's client events, wired once per client (ArmLink `start`): the connection state goes
 * into the store (no React), and the rest is handed to the link's hooks. A client the link has
 * let go of (stop/release) still emits close/offline and may still deliver what was already in
 * its socket: the store is the next link's by then, so those events are ignored (`isCurrent`).
 */
import type { ArmStore } from '../store/ArmStore.ts';
import type { MqttLike } from './MqttLike.ts';

/** CONNACK return codes of a refused log-in: MQTT 3.1.1's 4 and 5, MQTT 5's 134 and 135. */
const LOGIN_REFUSED = new Set<unknown>([4, 5, 134, 135]);

/** What the link does on its client's events (the store already says the new state). */
export interface ClientHooks {
  /** CONNACK (of the first connect or a reconnect). */
  connected(): void;
  /** The connection dropped (offline or close). */
  lost(): void;
  /** The broker refused the log-in; the client has been ended (no more reconnects). */
  authRefused(message: string): void;
  message(topic: string, payload: Uint8Array): void;
}

export function wireClient(
  client: MqttLike,
  isCurrent: () => boolean,
  store: Pick<ArmStore, 'connection' | 'connectionError'>,
  on: ClientHooks,
): void {
  client.on('connect', () => {
    store.connection = 'connected';
    store.connectionError = '';
    on.connected();
  });
  client.on('reconnect', () => isCurrent() && (store.connection = 'reconnecting'));
  client.on('offline', () => {
    if (!isCurrent()) return;
    store.connection = 'offline';
    on.lost();
  });
  client.on('close', () => {
    if (!isCurrent()) return;
    if (store.connection === 'connected' || store.connection === 'connecting')
      store.connection = 'offline';
    on.lost();
  });
  client.on('error', (err) => {
    if (!isCurrent()) return;
    store.connection = 'error';
    store.connectionError = err.message;
    if (LOGIN_REFUSED.has((err as Error & { code?: unknown }).code)) {
      // mqtt.js stops reconnecting after a refused CONNACK; make sure of it.
      client.end(true);
      on.authRefused(err.message.replace(/^Connection refused: /, ''));
    }
  });
  client.on('message', (topic, payload) => isCurrent() && on.message(topic, payload));
}
