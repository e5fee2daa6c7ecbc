/**
 * The embedded broker of the one-command demo: Aedes (in memory: retained messages and
 * sessions last as long as the process) serving MQTT over TCP (or TLS), and MQTT over
 * WebSockets at `/mqtt` on an HTTP(S) server (the HUD's own port, so the browser needs no
 * second origin). With a users file it authenticates and authorises every client (./auth.ts);
 * without one it is the anonymous local demo and refuses to listen beyond loopback.
 */
import http from 'node:http';
import type https from 'node:https';
import net from 'node:net';
import tls from 'node:tls';
import type { Duplex } from 'node:stream';
import { Aedes, type Client } from 'aedes';
import { MqttClient, type IClientOptions } from 'mqtt';
import { WebSocketServer, createWebSocketStream } from 'ws';
import { LoginThrottle, type Principal, type Users } from '@armtwin/auth';
import { MAX_PAYLOAD_BYTES } from '@armtwin/protocol';
import { duplexPair, installPolicy, limitPacketSize, type AuthCounters } from './auth.ts';

/** Takes an HTTP upgrade (returns true) or leaves it to the next handler. */
export type UpgradeHandler = (req: http.IncomingMessage, socket: Duplex, head: Buffer) => boolean;

export interface BrokerTls {
  /** PEM certificate chain and private key of the server. */
  cert: Buffer;
  key: Buffer;
}

export interface BrokerOptions {
  /** Interface the MQTT/TCP listener binds. */
  host: string;
  /** MQTT/TCP port; 0 = any free port. */
  port: number;
  /** When `port` is taken, listen on a free port instead of failing (the demo does this). */
  fallbackToFreePort: boolean;
  /** Path of the WebSockets endpoint on an attached HTTP server. */
  wsPath: string;
  /** Users and roles; null = anonymous local demo (loopback only). */
  users: Users | null;
  /** Serve MQTT over TLS (mqtts://) with this certificate; null = plain TCP. */
  tls: BrokerTls | null;
  /** Biggest MQTT packet accepted (remaining length), bytes; a bigger one closes the connection. */
  maxPacketBytes: number;
  /** Told about refused logins and denied publishes/subscriptions (the first of each is logged). */
  onDenied: (what: string, detail: Record<string, unknown>) => void;
}

export const DEFAULT_BROKER_OPTIONS: BrokerOptions = {
  host: '127.0.0.1',
  port: 1883,
  fallbackToFreePort: false,
  wsPath: '/mqtt',
  users: null,
  tls: null,
  maxPacketBytes: MAX_PAYLOAD_BYTES,
  onDenied: () => {},
};

export interface Broker {
  aedes: Aedes;
  /** The MQTT/TCP port actually listened on. */
  port: number;
  /** `mqtt://host:port` (or `mqtts://`) for local clients. */
  url: string;
  /** Whether `port` differs from the one asked for (it was taken). */
  fellBack: boolean;
  /** Whether clients must log in (a users file was given). */
  authenticated: boolean;
  counters: AuthCounters;
  /**
   * The users file behind the log-in throttle (null in the anonymous demo): `armtwin up` checks
   * HTTP Basic log-ins with it too, so one lockout covers MQTT and `/api`.
   */
  logins: LoginThrottle | null;
  /**
   * Serves MQTT over WebSockets on this HTTP(S) server at `wsPath`. `others` are offered each
   * upgrade first (a camera's stream, say); an upgrade nobody takes is closed.
   */
  attach(server: http.Server | https.Server, others?: readonly UpgradeHandler[]): void;
  /**
   * An mqtt.js client connected in-process (no socket, no password) with the rights of
   * `principal`: how `armtwin up` runs its own simulated arm and middleware.
   */
  connectInProcess(principal: Principal, options: IClientOptions): MqttClient;
  close(): Promise<void>;
}

export const isLoopback = (host: string): boolean =>
  host === 'localhost' || host === '::1' || /^127\.\d+\.\d+\.\d+$/.test(host);

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
  if (!o.users && !isLoopback(o.host))
    throw new Error(
      `refusing anonymous MQTT on ${o.host}: beyond loopback the broker needs a users file (ARMTWIN_USERS)`,
    );
  const aedes = await Aedes.createBroker();
  const counters: AuthCounters = {
    refusedLogins: 0,
    lockedOutLogins: 0,
    deniedPublish: 0,
    deniedSubscribe: 0,
    oversizePackets: 0,
  };
  const logins = o.users ? new LoginThrottle(o.users) : null;
  const policy = installPolicy(aedes, logins, counters, o.onDenied);
  const handle = (conn: Parameters<Aedes['handle']>[0], req?: http.IncomingMessage): Client => {
    const address = req?.socket.remoteAddress ?? (conn as Partial<net.Socket>).remoteAddress;
    if (address) policy.from(conn, address);
    const client = aedes.handle(conn, req as never);
    limitPacketSize(client, o.maxPacketBytes, () => {
      counters.oversizePackets++;
      o.onDenied('oversize', { client: client.id, maxBytes: o.maxPacketBytes });
    });
    return client;
  };
  const onSocket = (socket: net.Socket) => {
    socket.setNoDelay(true); // small frames go out at once, not after Nagle's ~40 ms
    handle(socket);
  };
  const tcp = o.tls
    ? tls.createServer({ cert: o.tls.cert, key: o.tls.key, minVersion: 'TLSv1.2' }, onSocket)
    : net.createServer(onSocket);
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
    url: `${o.tls ? 'mqtts' : 'mqtt'}://${host.includes(':') ? `[${host}]` : host}:${port}`,
    fellBack,
    authenticated: o.users !== null,
    counters,
    logins,
    attach(server, others = []) {
      // A WebSocket message carries one MQTT packet or a few; the exact bound is the parser's.
      const wss = new WebSocketServer({ noServer: true, maxPayload: 4 * o.maxPacketBytes });
      wss.on('connection', (ws, req) => {
        const stream = createWebSocketStream(ws);
        stream.on('error', () => ws.terminate());
        handle(stream, req);
      });
      const mqttUpgrade: UpgradeHandler = (req, socket, head) => {
        if (new URL(req.url ?? '/', 'http://x').pathname !== o.wsPath) return false;
        wss.handleUpgrade(req, socket, head, (ws) => wss.emit('connection', ws, req));
        return true;
      };
      server.on('upgrade', (req, socket, head) => {
        if (![...others, mqttUpgrade].some((take) => take(req, socket, head))) socket.destroy();
      });
      sockets.add(wss);
    },
    connectInProcess(principal, options) {
      return new MqttClient(() => {
        const [ours, theirs] = duplexPair();
        policy.trust(theirs, principal);
        handle(theirs);
        return ours;
      }, options);
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
