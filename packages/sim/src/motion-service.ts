/**
 * Motion requests, executed by the simulated controller (docs/protocol.md, "Motion requests").
 * JSON on `arm/{id}/request` is validated, planned from the pose the servos are in (with
 * `@armtwin/motion`) and answered on `arm/{id}/feedback`; `execute: true` then streams the
 * plan into the sim's own servos every `stepMs`, with pose checking: a servo off the plan
 * (a stall fault) pauses the arm and re-plans from where it is. An emergency stop
 * (`#255PDST!`), the deadman, a stop or any move on `arm/{id}/control`, or a newer request
 * ends an execution as `stopped`. The arm's profile is announced, retained, on
 * `arm/{id}/profile` at every (re)connect. The MQTT client and the clock are injected.
 */
import type { MqttClient } from 'mqtt';
import {
  CODE_INVALID,
  CODE_STOPPED,
  DEFAULT_EXECUTE_OPTIONS,
  PlanExecution,
  describeDeviation,
  outcomeFeedback,
  parseRequest,
  planRequest,
  planSummary,
  type ExecuteOptions,
  type MotionFeedback,
} from '@armtwin/motion';
import { armTopics, parseUserTopic, type Clock } from '@armtwin/protocol';
import type { SimProfile } from './profile.ts';
import { TokenBucket } from './rate-limit.ts';
import type { SimRunner } from './runner.ts';

export interface MotionServiceOptions {
  /** Pose checking and streaming (`DEFAULT_EXECUTE_OPTIONS` of @armtwin/motion). */
  execute: Partial<ExecuteOptions>;
  /** Requests per second accepted, sustained; beyond it a request is answered `failed`. */
  requestRate: number;
  /** Requests accepted at once after a quiet spell. */
  requestBurst: number;
  /**
   * Whether the sender of a request (`''`: the plain topic; else the user of
   * `arm/{id}/request/{user}`) may move the arm now: '' if so, else why not. An executing
   * request refused here is answered `failed` and nothing moves (one operator at a time,
   * docs/protocol.md § Control). Unset: everyone may.
   */
  mayExecute?: (user: string) => string;
}

export const DEFAULT_MOTION_SERVICE_OPTIONS: MotionServiceOptions = {
  execute: {},
  requestRate: 10,
  requestBurst: 20,
};

export interface MotionService {
  /** Counters by outcome, for logs. */
  readonly counters: Record<string, number>;
  stop(): void;
}

interface Running {
  id: string;
  exec: PlanExecution;
  /** Controller counters when it started: a change means someone else took the arm. */
  seen: string;
  emergencyStops: number;
  deadmanStops: number;
}

export function startMotionService(
  client: MqttClient,
  runner: SimRunner,
  armId: string,
  sim: SimProfile,
  clock: Clock,
  onFirst: (kind: string, message: string) => void,
  options: Partial<MotionServiceOptions> = {},
): MotionService {
  const o = { ...DEFAULT_MOTION_SERVICE_OPTIONS, ...options };
  const exo = { ...DEFAULT_EXECUTE_OPTIONS, ...o.execute };
  const topics = armTopics(armId);
  const model = runner.model;
  const servos = model.servos;
  const bucket = new TokenBucket(o.requestRate, o.requestBurst, clock.now());
  const counters: Record<string, number> = {};
  let running: Running | undefined;
  let timer: unknown;

  const send = (f: MotionFeedback) => {
    counters[f.status] = (counters[f.status] ?? 0) + 1;
    if (!client.connected) return;
    client.publish(topics.feedback, JSON.stringify({ ...f, t: Math.round(clock.now()) }), {
      qos: 1,
    });
  };
  const pose = (t: number) => Array.from({ length: servos.count }, (_, i) => servos.pwmAt(i, t));
  const controlCounters = () => {
    const c = model.counters;
    return `${c.moves},${c.groups},${c.kms},${c.stops},${c.emergencyStops}`;
  };

  const finish = () => {
    running = undefined;
    if (timer !== undefined) clock.clearTimeout(timer);
    timer = undefined;
  };
  const stopAll = (t: number) => {
    model.advance(t);
    for (let i = 0; i < servos.count; i++) servos.stop(i, t);
  };

  const tick = () => {
    timer = undefined;
    const r = running;
    if (!r) return;
    const t = clock.now();
    if (controlCounters() !== r.seen) {
      const why =
        runner.counters.deadmanStops > r.deadmanStops
          ? 'deadman: the operator let go'
          : model.counters.emergencyStops > r.emergencyStops
            ? 'emergency stop (#255PDST!)'
            : `a command on ${topics.control} took over`;
      send({ id: r.id, status: 'stopped', code: CODE_STOPPED, message: `stopped: ${why}` });
      return finish();
    }
    const step = r.exec.step(t, pose(t));
    switch (step.kind) {
      case 'move':
        model.advance(t);
        step.pwm.forEach((p, i) => servos.moveTo(i, p, step.ms, t));
        break;
      case 'pause':
        stopAll(t);
        send({
          id: r.id,
          status: 'executing',
          code: 0,
          event: 'paused',
          replans: r.exec.replans,
          servo: sim.profile.servos[step.check.worst]!.key,
          deviation: Math.round(step.check.deviation[step.check.worst]! * 10) / 10,
          message: `paused: ${describeDeviation(r.exec.robot, step.check, exo)}; re-planning from the actual pose in ${exo.pauseMs} ms`,
        });
        break;
      case 'replanned':
        send({
          id: r.id,
          status: 'executing',
          code: 0,
          event: 'replanned',
          replans: step.replans,
          message: `re-planned from the actual pose (${step.replans} of at most ${exo.maxReplans})`,
          ...planSummary(step.plan),
        });
        break;
      case 'done':
        send({
          id: r.id,
          status: 'done',
          code: 0,
          message: 'done',
          replans: r.exec.replans,
          ...planSummary(r.exec.plan),
        });
        return finish();
      case 'failed':
        stopAll(t);
        send({
          id: r.id,
          status: 'failed',
          code: step.code,
          message: step.message,
          replans: r.exec.replans,
        });
        return finish();
      case 'wait':
        break;
    }
    timer = clock.setTimeout(tick, exo.stepMs);
  };
  const onRequest = (payload: Buffer, user: string) => {
    const now = clock.now();
    if (!bucket.take(now)) {
      if ((counters.rateLimited = (counters.rateLimited ?? 0) + 1) === 1)
        onFirst('request:rate-limit', `motion requests over ${o.requestRate}/s refused`);
      const id = /"id"\s*:\s*"([A-Za-z0-9._:-]{1,64})"/.exec(
        payload.toString('utf8', 0, 2048),
      )?.[1];
      return send({
        id: id ?? null,
        status: 'failed',
        code: CODE_INVALID,
        message: 'rate limit: too many requests',
      });
    }
    const v = parseRequest(payload);
    if (!v.ok) {
      if ((counters.invalid = (counters.invalid ?? 0) + 1) === 1)
        onFirst('request:invalid', v.message);
      return send({
        id: v.id,
        status: 'failed',
        code: CODE_INVALID,
        message: v.message,
        field: v.field,
      });
    }
    const req = v.request;
    const refused = req.execute === true ? (o.mayExecute?.(user) ?? '') : '';
    if (refused)
      return send({
        id: req.id,
        status: 'failed',
        code: CODE_INVALID,
        message: `not executed: ${refused}`,
      });
    runner.model.advance(now);
    const outcome = planRequest(sim.robot, req, pose(now));
    send(outcome_(req.id, outcome, req.execute === true));
    if (outcome.status !== 'planned' || req.execute !== true) return;
    if (running) {
      send({
        id: running.id,
        status: 'stopped',
        code: CODE_STOPPED,
        message: `stopped: superseded by request ${req.id}`,
      });
      finish();
    }
    running = {
      id: req.id,
      exec: new PlanExecution(sim.robot, outcome.plan, outcome.spec, exo),
      seen: controlCounters(),
      emergencyStops: model.counters.emergencyStops,
      deadmanStops: runner.counters.deadmanStops,
    };
    send({
      id: req.id,
      status: 'executing',
      code: 0,
      event: 'started',
      message: 'executing',
      replans: 0,
      ...planSummary(outcome.plan),
    });
    tick();
  };
  const outcome_ = (
    id: string,
    outcome: Parameters<typeof outcomeFeedback>[1],
    execute: boolean,
  ) => {
    const f = outcomeFeedback(id, outcome);
    if (outcome.status === 'planned' && !execute) f.message += ' (plan only: nothing moves)';
    return f;
  };

  const onConnect = () => {
    client.publish(topics.profile, sim.announcement, { qos: 1, retain: true });
    client.subscribe([topics.request, `${topics.request}/+`], { qos: 1 }, (err) => {
      if (err) onFirst('subscribe', err.message);
    });
  };
  const onMessage = (topic: string, payload: Buffer) => {
    const byUser = parseUserTopic(topic);
    if (topic !== topics.request && !(byUser?.kind === 'request' && byUser.armId === armId)) return;
    try {
      onRequest(payload, byUser?.user ?? '');
    } catch (err) {
      // Never let a request take the controller down: answer it and carry on.
      const message = err instanceof Error ? err.message : String(err);
      onFirst('request:error', message);
      send({
        id: null,
        status: 'failed',
        code: CODE_INVALID,
        message: `internal error: ${message}`.slice(0, 200),
      });
    }
  };
  client.on('connect', onConnect);
  client.on('message', onMessage);
  if (client.connected) onConnect();

  return {
    counters,
    stop() {
      finish();
      client.removeListener('connect', onConnect);
      client.removeListener('message', onMessage);
    },
  };
}
