/**
 * Where the middleware's messages come from: an MQTT broker (or a list of them), or a NATS
 * cluster's JetStream (NATS_URL: one durable consumer shared by every middleware,
 * ./nats-intake.ts). Either way each message goes to the cleaner and the spool (a camera's
 * announcement to the recordings), is made durable at `commit`, and is acknowledged after it.
 */
import { describeBroker, redactBrokerUrl } from '@armtwin/link';
import { topicMatches } from '@armtwin/auth';
import type { MiddlewareConfig } from './config.ts';
import type { Ingest } from './ingest.ts';
import type { LogOnce, Logger } from './log.ts';
import type { Metrics } from './metrics.ts';
import { startMqtt, type ConnectFn, type MqttEdge, type MqttHandlers } from './mqtt.ts';
import { startNatsIntake } from './nats-intake.ts';
import type { Storage } from './storage.ts';
import { CAMERA_FILTER, type Recordings } from './cameras/index.ts';

export interface IntakeParts {
  ingest: Ingest;
  storage: Storage | null;
  recordings: Recordings | null;
  metrics: Metrics;
  log: Logger;
  once: LogOnce;
  /** Wall clock, epoch ms: the time of frames that carry no `$TIM`. */
  now: () => number;
  /** The middleware is stopping: a closed connection is not news. */
  stopped: () => boolean;
  /** mqtt.js `connect` (a fake in unit tests). */
  connect?: ConnectFn;
}

export function startIntake(config: MiddlewareConfig, p: IntakeParts): MqttEdge {
  const { ingest, storage, recordings, metrics, log, once, now } = p;
  const handlers: MqttHandlers = {
    onMessage: (topic, payload) => {
      // `includes` first: a cheap no for every arm's reports (arm/+/camera/+ has it)
      if (recordings && topic.includes('/camera/') && topicMatches(CAMERA_FILTER, topic))
        return recordings.handle(topic, payload);
      const lines = ingest.handle(topic, payload, now());
      storage?.add(lines);
    },
    commit: () => storage?.commit(),
    onConnect: () => {
      metrics.mqttConnected = true;
      metrics.mqttConnects++;
      once.reset('mqtt-error');
      const b = client.brokers.choice;
      metrics.mqttBroker = b.index + 1;
      log.info(
        {
          url: redactBrokerUrl(b.url),
          broker: b.index + 1,
          brokers: b.count,
          clientId: config.mqttClientId,
          qos: config.mqttQos,
          shareGroup: config.mqttShareGroup || undefined,
          natsConsumer: config.natsUrl ? config.natsConsumer : undefined,
        },
        config.natsUrl ? 'NATS connected' : 'MQTT connected',
      );
    },
    onClose: () => {
      if (metrics.mqttConnected && !p.stopped())
        log.warn(`${config.natsUrl ? 'NATS' : 'MQTT'} connection closed; reconnecting`);
      metrics.mqttConnected = false;
    },
    onError: (err) =>
      once.warn('mqtt-error', { err: err.message }, config.natsUrl ? 'NATS error' : 'MQTT error'),
    onMove: (move) => {
      if (!move.from) return;
      metrics.mqttBrokerMoves++;
      log.info(
        { from: move.from.index + 1, to: move.to.index + 1, reason: move.reason },
        `broker move: ${describeBroker(move.to)}`,
      );
    },
    gate: () => storage?.gate() ?? null,
  };
  const client: MqttEdge = config.natsUrl
    ? startNatsIntake(
        {
          url: config.natsUrl,
          consumer: config.natsConsumer,
          name: config.mqttClientId,
          username: config.mqttUsername,
          password: config.mqttPassword,
          reconnectMs: config.mqttReconnectMs,
          ackWaitMs: config.natsAckWaitMs,
          note: (message, fields) => log.info(fields, message),
        },
        handlers,
      )
    : startMqtt(
        {
          url: config.mqttUrl,
          username: config.mqttUsername,
          password: config.mqttPassword,
          clientId: config.mqttClientId,
          qos: config.mqttQos,
          keepaliveS: config.mqttKeepaliveS,
          reconnectMs: config.mqttReconnectMs,
          shareGroup: config.mqttShareGroup,
          extraTopics: recordings ? [CAMERA_FILTER] : [],
        },
        handlers,
        p.connect,
      );
  return client;
}
