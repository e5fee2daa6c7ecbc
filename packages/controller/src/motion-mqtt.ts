/**
 * Motion requests on MQTT, for any driver (`@armtwin/controller/mqtt`): subscribes
 * `arm/{id}/request` and `arm/{id}/request/+`, hands each request to `MotionRequests`, publishes
 * the feedback on `arm/{id}/feedback` (QoS 1, stamped `t`), and steps a running execution every
 * `stepMs` on the injected clock. With `announcement`, the arm's profile is published, retained,
 * on `arm/{id}/profile` at every (re)connect. The client and the clock are the driver's.
 */
import type { MqttClient } from 'mqtt';

import { armTopics, parseUserTopic, type Clock } from '@armtwin/protocol';
import { CODE_INVALID, type MotionFeedback } from '@armtwin/motion';
import type { MotionRequests } from './motion.ts';

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
    client.subscribe([topics.request, `${topics.request}/+`], { qos: 1 }, (err) => {
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
