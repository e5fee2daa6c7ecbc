/**
 * `armtwin broker`: the embedded broker on its own, MQTT/TCP (or TLS) and, when a WebSockets
 * port is given, MQTT over WebSockets at `/mqtt` on an HTTP(S) server of its own that answers
 * anything else with 404. Logs where it listens and who may connect; the caller decides when
 * to stop.
 */
import http from 'node:http';
import https from 'node:https';
import type { Logger } from 'pino';
import { startBroker, type Broker } from './broker.ts';
import { describeSecurity, type BrokerSecurity } from './security.ts';

export interface ServeBrokerOptions extends BrokerSecurity {
  host: string;
  /** MQTT/TCP port; 0 = any free port. */
  port: number;
  /** Also serve MQTT over WebSockets on this port (undefined = no). */
  wsPort?: number;
  log: Logger;
  /** Told about each refusal (the first of each kind is worth logging). */
  onDenied: (what: string, detail: Record<string, unknown>) => void;
}

export interface ServedBroker {
  broker: Broker;
  /** Closes the WebSockets server (if any) and the broker, then logs the counters. */
  stop(): Promise<void>;
}

export async function serveBroker(o: ServeBrokerOptions): Promise<ServedBroker> {
  const { log } = o;
  const broker = await startBroker({
    host: o.host,
    port: o.port,
    users: o.users,
    tls: o.tls,
    onDenied: o.onDenied,
  });
  let server: http.Server | https.Server | undefined;
  if (o.wsPort !== undefined) {
    const notFound = (_req: http.IncomingMessage, res: http.ServerResponse) =>
      res.writeHead(404).end();
    const ws = o.tls
      ? https.createServer({ ...o.tls, minVersion: 'TLSv1.2' }, notFound)
      : http.createServer(notFound);
    server = ws;
    broker.attach(ws);
    await new Promise<void>((resolve, reject) =>
      ws.once('error', reject).listen(o.wsPort, o.host, resolve),
    );
    const a = ws.address();
    log.info(
      {
        url: `${o.tls ? 'wss' : 'ws'}://${o.host}:${typeof a === 'object' && a ? a.port : o.wsPort}/mqtt`,
      },
      'MQTT over WebSockets',
    );
  }
  broker.aedes.on('client', (c) => log.debug({ id: c.id }, 'client connected'));
  log.info({ url: broker.url, security: describeSecurity(o, o.host) }, 'MQTT broker listening');
  return {
    broker,
    async stop() {
      server?.closeAllConnections();
      await broker.close();
      server?.close();
      log.info({ counters: broker.counters }, 'broker stopped');
    },
  };
}
