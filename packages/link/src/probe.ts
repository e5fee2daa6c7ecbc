/**
 * One probe of a broker: a client of its own connects (no retry, no last will), runs
 * `onConnected` (a part may register its persistent session there), and ends. Answers whether
 * the broker took the connection within `timeoutMs`. Never rejects.
 *
 * A probe never acknowledges what the broker delivers to it. With the part's own client id and a
 * persistent session, the broker sends that session's queue right behind the CONNACK:
 * acknowledged, it would be gone from the broker and never reach the part. Held unacknowledged,
 * it stays in the session and is sent again to the part's own connection. So the probe's
 * `handleMessage` never calls back, from the moment the client exists: mqtt.js's default
 * acknowledges, and mqtt.js emits 'connect' only after it has read what followed the CONNACK.
 */
import type { IClientOptions, MqttClient } from 'mqtt';

export type ConnectFn = (url: string, opts: IClientOptions) => MqttClient;

/**
 * Runs on a probe's connection. `held` resolves when the broker has delivered a message (held,
 * not acknowledged: mqtt.js then reads nothing more on that connection, not even a SUBACK).
 */
export type ProbeConnected = (client: MqttClient, held: Promise<void>) => Promise<void> | void;

export function probeBroker(
  connect: ConnectFn,
  url: string,
  opts: IClientOptions,
  timeoutMs: number,
  onConnected?: ProbeConnected,
): Promise<boolean> {
  return new Promise((resolve) => {
    let done = false;
    let client: MqttClient | null = null;
    const finish = (ok: boolean) => {
      if (done) return;
      done = true;
      clearTimeout(timer);
      client?.end(true);
      resolve(ok);
    };
    const timer = setTimeout(() => finish(false), timeoutMs);
    let onHeld = () => {};
    const held = new Promise<void>((r) => (onHeld = r));
    try {
      client = connect(url, {
        ...opts,
        will: undefined,
        reconnectPeriod: 0,
        connectTimeout: timeoutMs,
        manualConnect: true,
      });
    } catch {
      finish(false);
      return;
    }
    const c = client;
    // Never acknowledge (nor read past) a delivered message: see the head of this file.
    c.handleMessage = () => onHeld();
    c.on('connect', () => {
      Promise.resolve()
        .then(() => onConnected?.(c, held))
        .then(
          () => finish(true),
          () => finish(false),
        );
    });
    c.on('error', () => finish(false));
    c.on('close', () => finish(false));
    try {
      c.connect();
    } catch {
      finish(false);
    }
  });
}
