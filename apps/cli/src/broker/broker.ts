/**
 * The embedded broker of the one-command demo: Aedes (in memory: retained messages and
 * sessions last as long as the process) serving MQTT over TCP, and MQTT over WebSockets on an
 * HTTP server at `/mqtt` (the HUD's own port, so the browser needs no second origin).
 */
import http from 'node:http';
import net from 'node:net';
import { Aedes } from 'aedes';
import { WebSocketServer, createWebSocketStream } from 'ws';

export interface BrokerOptions {
  /** Interface the MQTT/TCP listener binds. */
  host: string;
  /** MQTT/TCP port; 0 = any free port. */
  port: number;
  /** When `port` is taken, listen on a free port instead of failing (the demo does this). */
  fallbackToFreePort: boolean;
  /** Path of the WebSockets endpoint on an attached HTTP server. */
  wsPath: string;
}

export const DEFAULT_BROKER_OPTIONS: BrokerOptions = {
  host: '127.0.0.1',
  port: 1883,
  fallbackToFreePort: false,
  wsPath: '/mqtt',
};

export interface Broker {
  aedes: Aedes;
  /** The MQTT/TCP port actually listened on. */
  port: number;
  /** `mqtt://host:port` for local clients. */
  url: string;
  /** Whether `port` differs from the one asked for (it was taken). */
  fellBack: boolean;
  /** Serves MQTT over WebSockets on this HTTP server at `wsPath`. */
  attach(server: http.Server): void;
  close(): Promise<void>;
}

function listen(server: net.Server, port: number, host: string): Promise<void> {
  return new Promise((resolve, reject) => {
    const onError = (err: Error) => reject(err);
    server.once('error', onError);
    server.listen({ port, host }, () => {
      server.removeListener('error', onError);
      resolve();
    });
  });
}

export async function startBroker(options: Partial<BrokerOptions> = {}): Promise<Broker> {
  const o = { ...DEFAULT_BROKER_OPTIONS, ...options };
  const aedes = await Aedes.createBroker();
  const tcp = net.createServer((socket) => aedes.handle(socket));
  let fellBack = false;
  try {
    await listen(tcp, o.port, o.host);
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code !== 'EADDRINUSE' || !o.fallbackToFreePort) {
      aedes.close();
      throw err;
    }
    fellBack = true;
    await listen(tcp, 0, o.host);
  }
  const address = tcp.address();
  const port = typeof address === 'object' && address ? address.port : o.port;
  const sockets = new Set<WebSocketServer>();
  const host = o.host === '0.0.0.0' || o.host === '::' ? '127.0.0.1' : o.host;

  return {
    aedes,
    port,
    url: `mqtt://${host.includes(':') ? `[${host}]` : host}:${port}`,
    fellBack,
    attach(server) {
      const wss = new WebSocketServer({ server, path: o.wsPath });
      wss.on('connection', (ws, req) => {
        const stream = createWebSocketStream(ws);
        stream.on('error', () => ws.terminate());
        aedes.handle(stream, req);
      });
      sockets.add(wss);
    },
    async close() {
      for (const wss of sockets) {
        for (const ws of wss.clients) ws.terminate();
        await new Promise<void>((resolve) => wss.close(() => resolve()));
      }
      await new Promise<void>((resolve) => aedes.close(() => resolve()));
      await new Promise<void>((resolve) => tcp.close(() => resolve()));
    },
  };
}
