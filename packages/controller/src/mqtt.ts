/**
 * The controller on MQTT, for any driver (`@armtwin/controller/mqtt`); the client and the clock
 * are the driver's.
 *
 * `mqttArbiter`: one operator at a time in front of the controller, its refusals as `$ERR` on
 * `arm/{id}/status`, the holder record retained on `arm/{id}/holder`, events on
 * `arm/{id}/audit` (with the core's keep-out refusals, `auditKeepOut`).
 *
 * `operatorDeadman` (./deadman.ts): the deadman on `arm/{id}/operator`, stopping a moving arm
 * through the driver when the operator lets go or its lease runs out. `driverControl`
 * (./driver-control.ts): the core, its control input and that deadman, as every gateway builds them.
 *
 * `startMotionService`: motion requests; subscribes
 * `arm/{id}/request` and `arm/{id}/request/+`, hands each request to `MotionRequests`, publishes
 * the feedback on `arm/{id}/feedback` (QoS 1, stamped `t`), and steps a running execution every
 * `stepMs` on the injected clock. With `announcement`, the arm's profile is published, retained,
 * on `arm/{id}/profile` at every (re)connect.
 *
 * `armSummary` (./summary-mqtt.ts): the arm's summary, retained on `arm/{id}/summary` at 2 Hz and
 * at once on an alarm, from the status payloads the driver publishes and the core.
 */
import type { MqttClient } from 'mqtt';

import {
  CLEAN_SESSION_SUBSCRIBE_QOS,
  armTopics,
  auditTopic,
  encodeControllerError,
  encodeTime,
  holderTopic,
  parseUserTopic,
  type Clock,
} from '@armtwin/protocol';
import { ControlArbiter, type ControlArbiterOptions } from './arbiter.ts';
import { auditKeepOut } from './audit.ts';
import type { ControllerCore } from './core.ts';
import { CODE_INVALID, type MotionFeedback } from '@armtwin/motion';
import type { MotionRequests } from './motion.ts';

export { operatorDeadman } from './deadman.ts';
export * from './driver-control.ts';
export * from './summary-mqtt.ts';

/**
 * A `ControlArbiter` for arm `armId` on this client: `forward` hands a payload that may reach
 * the arm to the driver; with `core`, its keep-out refusals go into the audit record. The
 * holder record is published at each `announce()` (call it at every connect); a refusal or the
 * holder record is dropped while offline, an audit event waits in the client's queue (QoS 1).
 */
export function mqttArbiter(
  client: MqttClient,
  armId: string,
  clock: Clock,
  core: (() => ControllerCore) | undefined,
  forward: (payload: Uint8Array | string) => void,
  options: Partial<ControlArbiterOptions> = {},
): ControlArbiter {
  const status = armTopics(armId).status;
  const control: ControlArbiter = new ControlArbiter(
    armId,
    {
      now: () => clock.now(),
      setTimeout: (fn, ms) => clock.setTimeout(fn, ms),
      clearTimeout: (handle) => clock.clearTimeout(handle),
      forward: core ? auditKeepOut(core, () => control, forward) : forward,
      refuse: (message) => {
        if (!client.connected) return;
        const payload = encodeTime(Math.round(clock.now())) + encodeControllerError(message);
        client.publish(status, payload, { qos: 0 });
      },
      holder: (record) => {
        if (client.connected)
          client.publish(holderTopic(armId), JSON.stringify(record), { qos: 1, retain: true });
      },
      audit: (event) => void client.publish(auditTopic(armId), JSON.stringify(event), { qos: 1 }),
    },
    options,
  );
  return control;
}

export interface MotionService {
  /** Counters by outcome, for logs. */
  readonly counters: Record<string, number>;
  stop(): void;
}

export function startMotionService(
  client: MqttClient,
  motion: MotionRequests,
  armId: string,
  clock: Clock,
  onFirst: (kind: string, message: string) => void,
  announcement?: () => string,
): MotionService {
  const topics = armTopics(armId);
  let timer: unknown;

  const publish = (feedback: MotionFeedback[]) => {
    if (!client.connected) return;
    for (const f of feedback)
      client.publish(topics.feedback, JSON.stringify({ ...f, t: Math.round(clock.now()) }), {
        qos: 1,
      });
  };
  const schedule = () => {
    if (timer !== undefined || !motion.running) return;
    timer = clock.setTimeout(tick, motion.stepMs);
  };
  const tick = () => {
    timer = undefined;
    publish(motion.step(clock.now()));
    schedule();
  };

  const onConnect = () => {
    if (announcement) client.publish(topics.profile, announcement(), { qos: 1, retain: true });
    client.subscribe([topics.request, `${topics.request}/+`], { qos: CLEAN_SESSION_SUBSCRIBE_QOS }, (err) => {
      if (err) onFirst('subscribe', err.message);
    });
  };
  const onMessage = (topic: string, payload: Buffer) => {
    const byUser = parseUserTopic(topic);
    if (topic !== topics.request && !(byUser?.kind === 'request' && byUser.armId === armId)) return;
    try {
      publish(motion.request(payload, byUser?.user ?? '', clock.now()));
      schedule();
    } catch (err) {
      // Never let a request take the controller down: answer it and carry on.
      const message = err instanceof Error ? err.message : String(err);
      onFirst('request:error', message);
      publish([
        {
          id: null,
          status: 'failed',
          code: CODE_INVALID,
          message: `internal error: ${message}`.slice(0, 200),
        },
      ]);
    }
  };
  client.on('connect', onConnect);
  client.on('message', onMessage);
  if (client.connected) onConnect();

  return {
    counters: motion.counters,
    stop() {
      motion.stop();
      if (timer !== undefined) clock.clearTimeout(timer);
      timer = undefined;
      client.removeListener('connect', onConnect);
      client.removeListener('message', onMessage);
    },
  };
}
