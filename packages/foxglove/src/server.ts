/**
 * armtwin's live Foxglove WebSocket server (`armtwin up --foxglove [PORT]`, docs/foxglove.md):
 * the protocol is `@foxglove/ws-protocol`'s `FoxgloveServer`, on a `ws` server that accepts both
 * subprotocols, `foxglove.websocket.v1` (Lichtblick, the npm client) and `foxglove.sdk.v1`
 * (Foxglove ≥ 2.x, foxglove_bridge ≥ 3.2, the SDKs): their messages are the same, only the name
 * differs, so one server serves every Foxglove and Lichtblick in use.
 *
 * Log-in: the WebSocket upgrade goes through the HTTP API's one log-in step (`authorize`, HTTP
 * Basic against the users file, the same throttle as the broker's); without a users file it is
 * the anonymous local demo and listens on loopback only. Every client sees every arm; a viewer
 * only watches (its publish and service calls are refused); an operator's commands travel
 * under its own MQTT identity (./session.ts), and a camera it watches is read with its own log-in
 * (./cameras.ts).
 */
import http from 'node:http';
import https from 'node:https';
import { ServerCapability, StatusLevel } from '@foxglove/ws-protocol';
import { FoxgloveServer } from './ws-protocol.ts';
import type { MqttClient } from 'mqtt';
import { WebSocketServer, type WebSocket } from 'ws';
import { basicCredentials, type LoginThrottle, type Principal } from '@armtwin/auth';
import { createAuthorize, isLoopback, refusal } from '@armtwin/http-api';
import { SYSTEM_CLOCK, type Clock } from '@armtwin/protocol';
import { ArmRegistry } from './arms.ts';
import { commandFrames, commandTopic } from './commands.ts';
import { serveAssets, serveServices, type ServerCounts } from './requests.ts';
import { Session, type ConnectAs } from './session.ts';
import { sendLatched } from './latched.ts';
import { watchSubscriptions } from './client-subscriptions.ts';
import { CameraChannels } from './cameras.ts';
import { stampOf } from './channels.ts';

/** The subprotocols accepted, the SDK's first (a client offering both gets it). */
export const SUBPROTOCOLS = ['foxglove.sdk.v1', 'foxglove.websocket.v1'] as const;
export const DEFAULT_FOXGLOVE_PORT = 8765;

export interface FoxgloveServerOptions {
  /** TCP port (0: any free one). */
  port: number;
  host: string;
  /** WSS with this PEM certificate and key (`armtwin up`'s ARMTWIN_TLS_CERT/KEY); null: ws. */
  tls: { cert: Buffer; key: Buffer } | null;
  /** The users file behind the log-in throttle; null: the anonymous demo, loopback only. */
  logins: LoginThrottle | null;
  /** The robot folders, searched in order (profiles, URDFs, meshes). */
  modelDirs: readonly string[];
  /** Reads what a viewer may (profiles, holders, status, audit, alerts). */
  watch: MqttClient;
  /** Reads the control topics, for the commanded targets (may be `watch` itself); absent: none. */
  control?: MqttClient;
  /** Connects as a client's own identity, for its commands. */
  connectAs: ConnectAs;
  clock?: Clock;
  onFirst: (kind: string, message: string) => void;
}

export interface ArmtwinFoxglove {
  /** `ws://host:port` (`wss://` with TLS). */
  url: string;
  port: number;
  counts: ServerCounts;
  registry: ArmRegistry;
  cameras: CameraChannels;
  stop(): Promise<void>;
}

export async function startFoxgloveServer(o: FoxgloveServerOptions): Promise<ArmtwinFoxglove> {
  if (!o.logins && !isLoopbackHost(o.host))
    throw new Error(
      `the Foxglove server listens beyond loopback (${o.host}) only with log-ins (ARMTWIN_USERS)`,
    );
  const clock = o.clock ?? SYSTEM_CLOCK;
  const counts: ServerCounts = { clients: 0, refusedLogins: 0, refused: 0, badCommands: 0 };
  const fox = new FoxgloveServer({
    name: 'armtwin',
    capabilities: [
      ServerCapability.clientPublish,
      ServerCapability.services,
      ServerCapability.assets,
    ],
    supportedEncodings: ['json'],
  });
  const sessions = new Map<WebSocket, Session>();
  const registry = new ArmRegistry({
    fox,
    mqtt: o.watch,
    ...(o.control ? { control: o.control } : {}),
    modelDirs: o.modelDirs,
    now: () => clock.now(),
    onHolder: (armId, record) => {
      for (const s of sessions.values()) s.onHolder(armId, record);
    },
    onFirst: o.onFirst,
  });
  const cameras = new CameraChannels(fox, o.watch);
  fox.on('error', (err) => o.onFirst(`client:${err.message}`, `Foxglove client: ${err.message}`));
  serveServices(fox, registry, (ws) => sessions.get(ws as WebSocket), counts);
  serveAssets(fox, o.modelDirs);
  fox.on('message', ({ client, channel, data }) => {
    const session = sessions.get(client.connection as WebSocket);
    const tell = (message: string) =>
      fox.sendStatus({ level: StatusLevel.ERROR, message }, client.connection);
    if (!session) return;
    const why = session.refusal;
    if (why) {
      counts.refused++;
      return tell(`${channel.topic}: refused: ${why}`);
    }
    const target = commandTopic(channel.topic);
    const arm = target && registry.arms.get(target.armId);
    if (!target || !arm) {
      counts.badCommands++;
      return tell(`${channel.topic}: no such command topic (/{arm}/joint_trajectory, /{arm}/jog)`);
    }
    const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    const r = commandFrames(arm.folder, arm.feed.pwm, target.command, bytes);
    switch (r.kind) {
      case 'move':
        return session.play(arm.id, r.frames);
      case 'stop':
        return session.stop(arm.id);
      case 'refused':
        counts.badCommands++;
        return tell(`${channel.topic}: ${r.message}`);
      default: {
        const never: never = r;
        return never;
      }
    }
  });

  const authorize = createAuthorize({ logins: o.logins, apiToken: '', anonymous: 'loopback' });
  const auth = { logins: o.logins, apiToken: '', anonymous: 'loopback' as const };
  let anonymous = 0;
  const wss = new WebSocketServer({
    noServer: true,
    handleProtocols: (offered) => SUBPROTOCOLS.find((p) => offered.has(p)) ?? false,
  });
  const onRequest = (_req: http.IncomingMessage, res: http.ServerResponse) =>
    res
      .writeHead(426, { 'content-type': 'text/plain' })
      .end(`armtwin's Foxglove WebSocket server: connect with ${SUBPROTOCOLS.join(' or ')}\n`);
  const server = o.tls
    ? https.createServer({ ...o.tls, minVersion: 'TLSv1.2' }, onRequest)
    : http.createServer(onRequest);
  server.on('upgrade', (req, socket, head) => {
    void authorize(req).then((caller) => {
      const no = refusal(auth, req, caller, 'view');
      if (no) {
        counts.refusedLogins++;
        socket.end(`HTTP/1.1 ${no.status} ${no.error}\r\nconnection: close\r\n\r\n`);
        return;
      }
      const who: Principal =
        caller.kind === 'user'
          ? caller.principal
          : { name: `foxglove-${++anonymous}`, role: 'operator' };
      wss.handleUpgrade(req, socket, head, (ws) => {
        counts.clients++;
        const password =
          caller.kind === 'user'
            ? (basicCredentials(req.headers.authorization ?? '')?.password ?? null)
            : null;
        sessions.set(ws, new Session(who, password, o.connectAs, clock));
        fox.handleConnection(ws, `${who.name} (${ws.protocol})`);
        // a camera is read with the client's own log-in (its Basic header; none in the demo)
        const camera = cameras.client(
          ws,
          caller.kind === 'user' ? (req.headers.authorization ?? null) : null,
        );
        watchSubscriptions(ws, {
          subscribe: (subId, channelId) => {
            sendLatched(ws, registry, subId, channelId, stampOf(clock.now()).ns);
            camera.subscribe(subId, channelId);
          },
          unsubscribe: camera.unsubscribe,
        });
        ws.on('close', () => {
          camera.close();
          void sessions.get(ws)?.close();
          sessions.delete(ws);
        });
      });
    });
  });
  await new Promise<void>((resolve, reject) => {
    server.once('error', reject);
    server.listen(o.port, o.host, () => resolve());
  });
  const address = server.address();
  const port = typeof address === 'object' && address ? address.port : o.port;
  const shown = o.host.includes(':') ? `[${o.host}]` : o.host;
  return {
    url: `${o.tls ? 'wss' : 'ws'}://${shown}:${port}`,
    port,
    counts,
    registry,
    cameras,
    async stop() {
      for (const ws of wss.clients) ws.terminate();
      await Promise.all([...sessions.values()].map((s) => s.close()));
      await new Promise<void>((resolve) => server.close(() => resolve()));
    },
  };
}

const isLoopbackHost = (host: string): boolean => host === 'localhost' || isLoopback(host);
