/**
 * Wires the gateway (what `armtwin gateway` runs): the robot profile read from disk (its limits
 * and zones checked by the controller core in front of the board, announced and followed:
 * ./arm-services.ts, with motion requests), a `SerialLink` (reopens with back-off) and an
 * mqtt.js client (reconnects every `reconnectMs`, last will `0` retained on `arm/{id}/online`),
 * both kept up on their own.
 */
import type { IClientOptions, MqttClient } from 'mqtt';
import type { Logger } from 'pino';
import {
  clientJoinedStream,
  connectBrokers,
  flushJoined,
  type BrokerClient,
  type JoinedStream,
} from '@armtwin/link';
import {
  numericKms,
  zonesKeepOut,
  type ControlArbiter,
  type ControllerCore,
} from '@armtwin/controller';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { armSummary, mqttArbiter, type ArmSummaryOut } from '@armtwin/controller/mqtt';
import {
  CLEAN_SESSION_SUBSCRIBE_QOS,
  armTopics,
  holderTopic,
  linkOptions,
  MQTT_KEEPALIVE_S,
  MQTT_RECONNECT_MS,
  OPERATOR_LEASE_MS,
  SYSTEM_CLOCK,
  topic,
} from '@armtwin/protocol';
import { describeBroker, parseBrokerList } from '@armtwin/link';
import { startArmServices } from './arm-services.ts';
import { GatewayCore } from './gateway.ts';
import { DEFAULT_SERIAL_LINK_OPTIONS, SerialLink, type SerialLinkOptions } from './serial-link.ts';

export interface GatewayOptions {
  serialPath: string;
  /** Robot profile of the arm: `<modelsDir>/<name>/profile.json` (ids, limits, keep-out zones, IK). */
  profile: string;
  modelsDir: string;
  baudRate: number;
  /** The broker, or an ordered comma-separated list (docs/protocol.md § Several brokers). */
  mqttUrl: string;
  armId: string;
  username?: string;
  password?: string;
  /** MQTT reconnect period, ms. */
  reconnectMs: number;
  /** MQTT keep-alive, s. */
  keepaliveS: number;
  /** A beating operator is let go after this long without a `1`, ms (0 = only a `0`). */
  operatorLeaseMs: number;
  serial: Partial<Omit<SerialLinkOptions, 'path' | 'baudRate'>>;
  onFirst: (kind: string, message: string) => void;
  /**
   * Logs the serial line and the broker coming and going, and the counters at stop (unset:
   * silent).
   */
  log?: Logger;
  /**
   * Makes the MQTT client from the gateway's options (client id, last will, link defaults)
   * instead of connecting to `mqttUrl`: `armtwin up` hands its gateway an in-process client of
   * the embedded broker with the device role. Unset: `mqttUrl`'s broker list.
   */
  connect?: (options: IClientOptions) => MqttClient;
}

/** A gateway's MQTT client; `brokers` is there when it follows a broker list (`mqttUrl`). */
export type GatewayClient = MqttClient & Partial<Pick<BrokerClient, 'brokers'>>;

export const DEFAULT_GATEWAY_OPTIONS = {
  baudRate: DEFAULT_SERIAL_LINK_OPTIONS.baudRate,
  modelsDir: MODELS_DIR,
  reconnectMs: MQTT_RECONNECT_MS,
  keepaliveS: MQTT_KEEPALIVE_S,
  operatorLeaseMs: OPERATOR_LEASE_MS,
  serial: {},
  onFirst: () => {},
} satisfies Partial<GatewayOptions>;

export interface Gateway {
  core: GatewayCore;
  /** Who holds the arm; only their moves reach the serial line. */
  control: ControlArbiter;
  client: MqttClient;
  link: SerialLink;
  stop(): Promise<void>;
}

/**
 * A gateway's MQTT client: its arm's `online` `0` as the last will, the shared link defaults,
 * no Nagle delay (frames are small; ~40 ms tails otherwise), and the broker list of `mqttUrl`
 * followed (`@armtwin/link`): a move is logged, one line each.
 */
export function connectGatewayMqtt(o: GatewayOptions): GatewayClient {
  const options: IClientOptions = {
    clientId: `armtwin-gateway-${o.armId}-${process.pid}`,
    ...(o.username ? { username: o.username, password: o.password ?? '' } : {}),
    will: { topic: topic(o.armId, 'online'), payload: Buffer.from('0'), qos: 1, retain: true },
    ...linkOptions({ keepalive: o.keepaliveS, reconnectPeriod: o.reconnectMs }),
    queueQoSZero: false,
  };
  if (o.connect) return o.connect(options);
  const client = connectBrokers(parseBrokerList(o.mqttUrl), options, {
    onMove: (move) =>
      move.from &&
      o.log?.info(
        { arm: o.armId, from: move.from.index + 1, to: move.to.index + 1, reason: move.reason },
        `broker move: ${describeBroker(move.to)}`,
      ),
  });
  client.on('connect', () =>
    (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true),
  );
  return client;
}

/**
 * How a gateway publishes: while connected, as asked; with several brokers the status stream
 * goes at QoS 1 and waits in the client's queue while a move is under way (nothing published
 * during a move is lost); anything else is dropped while offline (presence is re-sent on connect).
 * With `summary`, each status payload is also read by the arm's summary.
 */
export function gatewayPublish(
  client: GatewayClient,
  summary?: Pick<ArmSummaryOut, 'note'>,
): (topic: string, payload: Buffer | string, opts: { qos: 0 | 1; retain: boolean }) => void {
  const several = (client.brokers?.urls.length ?? 1) > 1;
  // QoS 1: one report message unacknowledged at a time, the rest joined (link/joined-stream.ts).
  const joined = new Map<string, JoinedStream>();
  const stream = (t: string) => {
    let s = joined.get(t);
    if (!s) joined.set(t, (s = clientJoinedStream(client, t)));
    return s;
  };
  return (t, payload, opts) => {
    // The arm's summary reads every status payload (docs/protocol.md § Fleets).
    if (summary && t.endsWith('/status')) summary.note(payload);
    if (several && !opts.retain && t.endsWith('/status'))
      stream(t).send(typeof payload === 'string' ? Buffer.from(payload) : payload);
    else if (client.connected) client.publish(t, payload, opts);
  };
}

/** What a gateway's core takes from MQTT. */
export interface GatewayMqttCore {
  brokerConnected(connected: boolean): void;
  fromControl(payload: Buffer): void;
  fromOperator(payload: Buffer): void;
  /** A bus arm's controller core: its keep-out refusals go into the audit record. */
  readonly controller?: ControllerCore;
}

/**
 * Subscribes the arm's control and operator topics (and `extra`: topic → handler) at every
 * connect, hands their messages to `core`, and tells it when the broker comes and goes.
 * Control goes through a `ControlArbiter` (one operator at a time, docs/protocol.md), which
 * also takes the per-user control, claim and override topics; it is returned.
 */
export function wireGatewayMqtt(
  client: MqttClient,
  o: Pick<GatewayOptions, 'armId' | 'log' | 'onFirst'> & { operatorLeaseMs?: number },
  core: GatewayMqttCore,
  extra: Record<string, (payload: Buffer) => void> = {},
): ControlArbiter {
  const topics = armTopics(o.armId);
  const controller = core.controller;
  const control = mqttArbiter(
    client,
    o.armId,
    SYSTEM_CLOCK,
    controller && (() => controller),
    (payload) => core.fromControl(Buffer.from(payload)),
    o.operatorLeaseMs === undefined ? {} : { leaseMs: o.operatorLeaseMs },
  );
  const handlers: Record<string, (payload: Buffer) => void> = {
    [topics.operator]: (p) => core.fromOperator(p),
    ...extra,
  };
  client.on('connect', () => {
    const b = (client as { brokers?: BrokerClient['brokers'] }).brokers?.choice;
    o.log?.info(
      { arm: o.armId, ...(b ? { broker: b.index + 1, brokers: b.count } : {}) },
      'broker connected',
    );
    core.brokerConnected(true);
    client.subscribe(
      [topics.control, ...control.filters, ...Object.keys(handlers)],
      { qos: CLEAN_SESSION_SUBSCRIBE_QOS },
      (err) => err && o.onFirst('subscribe', err.message),
    );
    control.announce();
  });
  client.on('close', () => core.brokerConnected(false));
  client.on('offline', () => o.log?.warn('broker unreachable; reconnecting'));
  client.on('error', (err) => o.onFirst(`mqtt:${err.message}`, `mqtt: ${err.message}`));
  client.on('message', (topic, payload) => {
    if (!control.fromMessage(topic, payload)) handlers[topic]?.(payload);
  });
  return control;
}

/**
 * A gateway's last words on its way out: the arm offline and nobody holding it (both retained),
 * then the client closed. Errors are ignored: the broker may be gone already (the will says 0).
 */
export async function leaveGatewayMqtt(client: MqttClient, armId: string): Promise<void> {
  flushJoined(client); // the reports still waiting go before the client ends
  if (client.connected) {
    await client
      .publishAsync(topic(armId, 'online'), '0', { qos: 1, retain: true })
      .catch(() => {});
    await client.publishAsync(holderTopic(armId), '', { qos: 1, retain: true }).catch(() => {});
  }
  await client.endAsync().catch(() => {});
}

export function startGateway(
  options: Partial<GatewayOptions> &
    Pick<GatewayOptions, 'serialPath' | 'mqttUrl' | 'armId' | 'profile'>,
): Gateway {
  const o: GatewayOptions = { ...DEFAULT_GATEWAY_OPTIONS, ...options };
  const { log } = o;
  const { profile, robot, raw } = readRobotFolder(o.profile, o.modelsDir);
  const client = connectGatewayMqtt(o);
  const link: SerialLink = new SerialLink(
    { ...o.serial, path: o.serialPath, baudRate: o.baudRate },
    {
      onOpen: () => {
        core.serialOpened();
        log?.info({ serial: o.serialPath }, 'serial line open');
      },
      onClose: (reason) => {
        core.serialClosed();
        log?.warn({ reason }, 'serial line closed; reopening');
      },
      onData: (chunk) => core.fromSerial(chunk),
    },
  );
  const summary = armSummary(client, o.armId, SYSTEM_CLOCK);
  const core = new GatewayCore(
    {
      armId: o.armId,
      profile,
      kms: numericKms(robot),
      keepOut: zonesKeepOut(robot),
      robot,
      operatorLeaseMs: o.operatorLeaseMs,
    },
    {
      ...SYSTEM_CLOCK,
      publish: gatewayPublish(client, summary),
      write: (data) => link.write(data),
      onFirst: o.onFirst,
    },
  );
  const control = wireGatewayMqtt(client, o, core);
  const services = startArmServices({ ...o, client, raw, robot, core, control });
  summary.start(
    () => core.controller,
    () => control.holder,
  );
  link.start();
  log?.info({ arm: o.armId, profile: o.profile }, 'gateway running');
  return {
    core,
    control,
    client,
    link,
    async stop() {
      services.stop();
      core.operator.reset();
      control.reset();
      await summary.stop();
      await leaveGatewayMqtt(client, o.armId);
      await link.stop();
      log?.info({ counters: core.counters, serial: link.counters }, 'gateway stopped');
    },
  };
}
