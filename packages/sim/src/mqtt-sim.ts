/**
 * The simulated arm on MQTT (its controller is @armtwin/controller's core, the servo model its
 * driver): the runner's status payloads go to `arm/{id}/status` (QoS 0),
 * `arm/{id}/control` feeds it, `arm/{id}/sim` takes fault commands (JSON, see faults.ts) and
 * the faults in force are published retained on `arm/{id}/sim/faults`. Presence: retained `1`
 * on `arm/{id}/online` at every (re)connect; the client must be created with the retained `0`
 * will (see `simWill`), and `stop()` publishes `0` itself before disconnecting.
 * Deadman: `arm/{id}/operator` is watched (`OperatorWatch`): a `0` there (the operator let go,
 * or the broker published its last will because its page dropped), or a beating operator whose
 * lease ran out, stops a moving arm (`runner.operatorLeft`).
 * One operator at a time: control comes in through a `ControlArbiter` (@armtwin/controller), which
 * keeps who holds the arm (retained on `arm/{id}/holder`), takes claims on `arm/{id}/claim/+`
 * and `arm/{id}/override/+`, lets only the holder's moves through and reports on
 * `arm/{id}/audit` (docs/protocol.md, "Control: one operator at a time").
 * The arm's summary (state, health, holder, pose) goes retained to `arm/{id}/summary` at 2 Hz and
 * at once on an alarm (`armSummary` of @armtwin/controller).
 * The MQTT client is injected.
 */
import type { IClientOptions, MqttClient } from 'mqtt';
import {
  CLEAN_SESSION_SUBSCRIBE_QOS,
  armTopics,
  holderTopic,
  OPERATOR_LEASE_MS,
  OperatorWatch,
  SYSTEM_CLOCK,
  type Clock,
} from '@armtwin/protocol';
import { MotionRequests, type ControlArbiter } from '@armtwin/controller';
import { clientJoinedStream, flushJoined } from '@armtwin/link';
import {
  armSummary,
  type ArmSummaryOut,
  mqttArbiter,
  operatorDeadman,
  startMotionService,
} from '@armtwin/controller/mqtt';
import { parseFaults } from './faults.ts';
import type { SimProfile } from './profile.ts';
import { SimRunner, type PayloadKind, type SimRunnerOptions } from './runner.ts';

export interface MqttSimOptions extends Partial<SimRunnerOptions> {
  /** The arm id: `[a-z0-9-]{1,32}`. */
  armId: string;
  clock?: Clock;
  /** The arm's profile: announced on `arm/{id}/profile`, and motion requests served (MotionRequests of @armtwin/controller). */
  profile?: SimProfile;
  /** A beating operator is let go after this long without a `1` (0 = only a `0` lets go). */
  operatorLeaseMs?: number;
  /**
   * QoS of the status stream (default 0: not queued while offline). With several brokers it is
   * 1: what is published during a move waits in the client's queue and goes to the next broker,
   * where the middleware's session keeps it (docs/protocol.md § Several brokers).
   */
  statusQos?: 0 | 1;
}

export interface MqttSim {
  runner: SimRunner;
  operator: OperatorWatch;
  /** Who holds the arm; only their moves reach the runner. */
  control: ControlArbiter;
  /** Status payloads handed to the client, by kind (queued ones included; not dropped ones). */
  published: Record<PayloadKind, number>;
  /** The `$TIM` samples in those payloads, by kind (what a store should hold of this arm). */
  publishedSamples: Record<PayloadKind, number>;
  /** Status messages handed to the client: the payloads, or fewer when joined (QoS 1). */
  readonly statusMessages: number;
  /** The arm's summary on `arm/{id}/summary` (docs/protocol.md § Fleets). */
  summary: ArmSummaryOut;
  /** Publishes online `0` (retained), stops the loops, ends the client. */
  stop(): Promise<void>;
}

export const simTopics = (armId: string) => {
  const t = armTopics(armId);
  return { ...t, sim: `arm/${armId}/sim`, simFaults: `arm/${armId}/sim/faults` };
};

/** The last will every arm client must connect with: retained `0` on `arm/{id}/online`. */
export const simWill = (armId: string): IClientOptions['will'] => ({
  topic: armTopics(armId).online,
  payload: Buffer.from('0'),
  qos: 1,
  retain: true,
});

export function startMqttSim(client: MqttClient, options: MqttSimOptions): MqttSim {
  const topics = simTopics(options.armId);
  const onFirst = options.onFirst ?? (() => {});
  const clock = options.clock ?? SYSTEM_CLOCK;
  let offlineDrops = 0;
  const published: Record<PayloadKind, number> = { state: 0, health: 0, reply: 0 };
  const publishedSamples: Record<PayloadKind, number> = { state: 0, health: 0, reply: 0 };
  const summary = armSummary(client, options.armId, clock);
  // QoS 1: one report message unacknowledged at a time, the rest joined (link/joined-stream.ts).
  const joined = options.statusQos === 1 ? clientJoinedStream(client, topics.status) : undefined;
  const runner = new SimRunner(
    {
      send(payload, kind, samples) {
        summary.note(payload);
        if (joined) {
          joined.send(payload); // queued while offline
          published[kind]++;
          publishedSamples[kind] += samples;
          return;
        }
        // QoS 0 and not queued while offline: a stale state stream is worse than a gap.
        if (!client.connected) {
          if (offlineDrops++ === 0)
            onFirst('offline', 'broker unreachable: status payloads dropped');
          return;
        }
        client.publish(topics.status, payload, { qos: 0 });
        published[kind]++;
        publishedSamples[kind] += samples;
      },
    },
    clock,
    options,
  );

  const operator = operatorDeadman(
    clock,
    () => runner.operatorLeft(),
    onFirst,
    options.operatorLeaseMs ?? OPERATOR_LEASE_MS,
  );

  const control = mqttArbiter(
    client,
    options.armId,
    clock,
    () => runner.model.core,
    (payload) => runner.receive(payload),
    { leaseMs: options.operatorLeaseMs ?? OPERATOR_LEASE_MS },
  );

  const publishFaults = (error?: string) =>
    client.publish(
      topics.simFaults,
      JSON.stringify({ ...runner.faults, ...(error ? { error } : {}) }),
      {
        qos: 1,
        retain: true,
      },
    );

  const onConnect = () => {
    client.publish(topics.online, '1', { qos: 1, retain: true });
    client.subscribe(
      [topics.control, topics.sim, topics.operator, ...control.filters],
      { qos: CLEAN_SESSION_SUBSCRIBE_QOS },
      (err) => {
        if (err) onFirst('subscribe', err.message);
      },
    );
    publishFaults();
    control.announce();
  };
  const onMessage = (topic: string, payload: Buffer) => {
    if (control.fromMessage(topic, payload)) return;
    if (topic === topics.operator) return operator.receive(payload);
    if (topic !== topics.sim) return;
    try {
      runner.applyFaults(parseFaults(payload.toString('utf8')));
      publishFaults();
    } catch (err) {
      const message = err instanceof Error ? err.message : String(err);
      onFirst('fault', message);
      publishFaults(message);
    }
  };
  client.on('connect', onConnect);
  client.on('message', onMessage);
  if (client.connected) onConnect();
  runner.start();
  summary.start(
    () => runner.model.core,
    () => control.holder,
  );
  const sim = options.profile;
  const motion = sim
    ? startMotionService(
        client,
        new MotionRequests(runner.model.core, () => sim.robot, clock.now(), {
          mayExecute: (user) => control.refusal(user, 'a motion request on the arm'),
          onFirst,
          controlTopic: topics.control,
        }),
        options.armId,
        clock,
        onFirst,
        () => sim.announcement,
      )
    : undefined;

  return {
    runner,
    operator,
    control,
    published,
    publishedSamples,
    get statusMessages() {
      return joined ? joined.sent : published.state + published.health + published.reply;
    },
    summary,
    async stop() {
      operator.reset();
      control.reset();
      runner.stop();
      motion?.stop();
      client.removeListener('message', onMessage);
      client.removeListener('connect', onConnect);
      await summary.stop();
      flushJoined(client); // the reports still waiting go before the client ends
      if (client.connected) {
        await client.publishAsync(topics.online, '0', { qos: 1, retain: true }).catch(() => {});
        await client.publishAsync(topics.simFaults, '', { qos: 1, retain: true }).catch(() => {});
        await client
          .publishAsync(holderTopic(options.armId), '', { qos: 1, retain: true })
          .catch(() => {});
      }
      await client.endAsync().catch(() => {});
    },
  };
}
