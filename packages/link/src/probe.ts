/**
 * One probe of a broker: a client of its own connects (no retry, no last will), runs
 * `onConnected` (the middleware registers its session there), and ends. Answers whether the
 * broker took the connection within `timeoutMs`. Never rejects.
 */
import type { IClientOptions, MqttClient } from 'mqtt';

export type ConnectFn = (url: string, opts: IClientOptions) => MqttClient;

export function probeBroker(
  connect: ConnectFn,
  url: string,
  opts: IClientOptions,
  timeoutMs: number,
  onConnected?: (client: MqttClient) => Promise<void> | void,
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
    try {
      client = connect(url, {
        ...opts,
        will: undefined,
        reconnectPeriod: 0,
        connectTimeout: timeoutMs,
        manualConnect: false,
      });
    } catch {
      finish(false);
      return;
    }
    const c = client;
    c.on('connect', () => {
      Promise.resolve()
        .then(() => onConnected?.(c))
        .then(
          () => finish(true),
          () => finish(false),
        );
    });
    c.on('error', () => finish(false));
    c.on('close', () => finish(false));
  });
}
