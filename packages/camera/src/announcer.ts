/**
 * Announces one camera on MQTT (PROTOCOL.md §7): its JSON retained at QoS 1 on
 * `arm/{armId}/camera/{camId}`, published again on every (re)connect; an empty retained
 * payload as the last will, so the camera of a server that dies disappears; and the same empty
 * payload, acknowledged, when it stops cleanly. One MQTT connection per camera, because a
 * connection has one will.
 */
import mqtt, { type IClientOptions, type MqttClient } from 'mqtt';
import type { Logger } from 'pino';
import { linkOptions, MQTT_KEEPALIVE_S, MQTT_RECONNECT_MS } from '@armtwin/protocol';
import { encodeAnnouncement, type CameraAnnouncement } from './announcement.ts';

export interface AnnouncerOptions {
  mqttUrl: string;
  /** Broker credentials ('' = anonymous). */
  username: string;
  password: string;
  topic: string;
  announcement: CameraAnnouncement;
  keepaliveS: number;
  reconnectMs: number;
  /** How long `stop()` waits for the broker to take the removal, ms. */
  stopTimeoutMs: number;
  onFirst: (kind: string, message: string) => void;
  /**
   * Makes the MQTT client (default `mqtt.connect`); `armtwin up` passes its embedded broker's
   * in-process connection, with a device principal of the arm.
   */
  connect: (url: string, options: IClientOptions) => MqttClient;
  log?: Logger;
}

export const DEFAULT_ANNOUNCER_OPTIONS = {
  username: '',
  password: '',
  keepaliveS: MQTT_KEEPALIVE_S,
  reconnectMs: MQTT_RECONNECT_MS,
  stopTimeoutMs: 3000,
  onFirst: () => {},
  connect: (url: string, options: IClientOptions) => mqtt.connect(url, options),
} satisfies Partial<AnnouncerOptions>;

export interface Announcer {
  client: MqttClient;
  /** Resolves once the broker has acknowledged the first announcement. */
  announced: Promise<void>;
  /** Removes the camera (empty retained payload, acknowledged) and disconnects. */
  stop(): Promise<void>;
}

const EMPTY = Buffer.alloc(0);
const RETAINED = { qos: 1, retain: true } as const;

export function startAnnouncer(
  options: Partial<AnnouncerOptions> & Pick<AnnouncerOptions, 'mqttUrl' | 'topic' | 'announcement'>,
): Announcer {
  const o: AnnouncerOptions = { ...DEFAULT_ANNOUNCER_OPTIONS, ...options };
  const payload = encodeAnnouncement(o.announcement);
  const client = o.connect(o.mqttUrl, {
    clientId: `armtwin-camera-${o.topic.split('/').slice(1).join('-')}-${process.pid}`.slice(
      0,
      120,
    ),
    ...(o.username ? { username: o.username, password: o.password } : {}),
    will: { topic: o.topic, payload: EMPTY, ...RETAINED },
    ...linkOptions({ keepalive: o.keepaliveS, reconnectPeriod: o.reconnectMs }),
  });
  let resolveAnnounced!: () => void;
  const announced = new Promise<void>((r) => (resolveAnnounced = r));
  let stopping = false;
  client.on('connect', () => {
    if (stopping) return;
    client.publish(o.topic, payload, RETAINED, (err) => {
      if (err) o.onFirst('announce', `camera announcement on ${o.topic} failed: ${err.message}`);
      else {
        o.log?.info({ topic: o.topic, url: o.announcement.url }, 'camera announced');
        resolveAnnounced();
      }
    });
  });
  client.on('offline', () => o.log?.warn({ topic: o.topic }, 'broker unreachable; reconnecting'));
  client.on('error', (err) => o.onFirst(`mqtt:${err.message}`, `mqtt: ${err.message}`));
  return {
    client,
    announced,
    async stop() {
      stopping = true;
      if (client.connected) {
        const removed = client.publishAsync(o.topic, EMPTY, RETAINED);
        const timeout = new Promise<'timeout'>((r) =>
          setTimeout(() => r('timeout'), o.stopTimeoutMs).unref(),
        );
        const r = await Promise.race([removed.then(() => 'ok' as const), timeout]).catch(
          (err: Error) => err.message,
        );
        if (r !== 'ok') o.onFirst('unannounce', `camera removal on ${o.topic}: ${r}`);
      }
      await client.endAsync();
    },
  };
}
