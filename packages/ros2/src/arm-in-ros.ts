/**
 * `armtwin ros2 --arm ID`: an armtwin arm as a ROS 2 arm. The composition root: an MQTT client
 * (the arm's status and holder record in, frames and claims out under the bridge's own user) and
 * the rclpy bridge process (joint states and the latched robot description out, trajectories in).
 *
 * - `<ns>/joint_states`: every status payload that moved a servo (./joint-states.ts).
 * - `<ns>/robot_description`: the profile's URDF, transient local (latched), as
 *   robot_state_publisher's parameter-topic is.
 * - `<ns>/joint_trajectory`: each JointTrajectory becomes timed move frames on
 *   `arm/{id}/control/{user}` (./trajectory.ts): the controller lets them through only from the
 *   holder, and checks limits, floor and zones as for any command. A new one replaces the one
 *   under way; losing the arm to someone else cancels it.
 */
import fs from 'node:fs';
import path from 'node:path';
import { connectBrokers, type BrokerClient } from '@armtwin/link';
import { readRobotFolder, MODELS_DIR } from '@armtwin/motion/robot-folder';
import {
  CLEAN_SESSION_SUBSCRIBE_QOS,
  encodeStop,
  linkOptions,
  parseHolder,
  topic,
  holderTopic,
  userTopic,
} from '@armtwin/protocol';
import { parseBrokerList } from '@armtwin/link';
import { Ros2Bridge } from './bridge-process.ts';
import { ClaimKeeper } from './claim-keeper.ts';
import { FrameStreamer } from './frame-streamer.ts';
import { JointStateBuilder } from './joint-states.ts';
import {
  armRosTopics,
  DEFAULT_ARM_IN_ROS_OPTIONS,
  type ArmInRosOptions,
} from './arm-in-ros-options.ts';
import { TRAJECTORY_REFUSALS, trajectoryFrames, type TrajectoryRefusal } from './trajectory.ts';
import type { JointTrajectoryMsg } from './wire.ts';

export interface ArmInRosCounts {
  jointStates: number;
  trajectories: number;
  stops: number;
  refused: Record<TrajectoryRefusal, number>;
  badHolder: number;
  /** Trajectory frames dropped because the broker was not connected. */
  notConnected: number;
}

export interface ArmInRos {
  readonly topics: ReturnType<typeof armRosTopics>;
  readonly counts: ArmInRosCounts;
  readonly bridge: Ros2Bridge;
  readonly mqtt: BrokerClient;
  readonly claims: ClaimKeeper;
  /** Resolves with the reason if the rclpy process ends before `stop()`. */
  readonly lost: Promise<string>;
  stop(): Promise<void>;
}

export async function startArmInRos(options: Partial<ArmInRosOptions> = {}): Promise<ArmInRos> {
  const o = { ...DEFAULT_ARM_IN_ROS_OPTIONS, ...options };
  const modelsDir = o.modelsDir ?? MODELS_DIR;
  const { profile, robot } = readRobotFolder(o.profile, modelsDir);
  const urdf = fs.readFileSync(path.join(modelsDir, o.profile, profile.urdf), 'utf8');
  const topics = armRosTopics(o.armId, o.namespace);
  const counts: ArmInRosCounts = {
    jointStates: 0,
    trajectories: 0,
    stops: 0,
    refused: Object.fromEntries(
      TRAJECTORY_REFUSALS.map((r) => [r, 0]),
    ) as ArmInRosCounts['refused'],
    badHolder: 0,
    notConnected: 0,
  };

  const bridge = await Ros2Bridge.start({
    domain: o.domain,
    nodeName: `armtwin_${o.armId.replace(/-/g, '_')}`,
    env: o.env,
    onError: (kind, message) => o.onFirst(`ros2-${kind}`, `ROS 2 bridge: ${message}`),
  });
  bridge.publish(topics.robotDescription, 'string', { data: urdf }, { durable: true });

  const control = userTopic(o.armId, 'control', o.user);
  const mqtt = connectBrokers(parseBrokerList(o.mqttUrl), {
    clientId: `armtwin-ros2-${o.armId}-${process.pid}`,
    ...(o.username ? { username: o.username, password: o.password ?? '' } : {}),
    ...linkOptions(),
  });
  // A move is sent only while connected: queued in the client, it would reach the arm late.
  const send = (payload: string) => {
    if (mqtt.connected) mqtt.publish(control, payload, { qos: 1 });
    else {
      counts.notConnected++;
      streamer.cancel();
      o.onFirst(
        'not-connected',
        `not connected to the broker: a trajectory for ${o.armId} was dropped`,
      );
    }
  };
  const streamer: FrameStreamer = new FrameStreamer(o.clock, send);
  const claims = new ClaimKeeper(o.user, o.take, o.clock, (payload) =>
    mqtt.publish(userTopic(o.armId, 'claim', o.user), payload, { qos: 1 }),
  );
  const builder = new JointStateBuilder(profile);
  const status = topic(o.armId, 'status');
  const holder = holderTopic(o.armId);

  mqtt.on('message', (t, payload) => {
    if (t === status) {
      const js = builder.feed(payload);
      if (js) {
        counts.jointStates++;
        bridge.publish(topics.jointStates, 'joint_state', js);
      }
    } else if (t === holder) {
      const record = parseHolder(payload);
      if (!record) {
        counts.badHolder++;
        return o.onFirst('bad-holder', `unreadable holder record on ${holder}`);
      }
      const held = claims.holds;
      claims.onHolder(record);
      if (held !== claims.holds)
        o.onInfo(
          claims.holds ? `${o.user} holds ${o.armId}` : `${o.user} no longer holds ${o.armId}`,
        );
      if (record.user !== null && !claims.holds) streamer.cancel();
    }
  });
  mqtt.on('error', (err) => o.onFirst(`mqtt:${err.message}`, `mqtt: ${err.message}`));
  mqtt.on('connect', () => {
    mqtt.subscribe([status, holder], { qos: CLEAN_SESSION_SUBSCRIBE_QOS });
  });

  const onTrajectory = (traj: JointTrajectoryMsg) => {
    const r = trajectoryFrames(profile, robot.table, builder.pwm, traj, o.stepMs);
    switch (r.kind) {
      case 'move':
        counts.trajectories++;
        streamer.play(r.frames);
        return;
      case 'stop':
        counts.stops++;
        streamer.cancel();
        send(r.ids.map(encodeStop).join(''));
        return;
      case 'refused':
        counts.refused[r.reason]++;
        o.onFirst(`trajectory-${r.reason}`, `trajectory refused: ${r.message}`);
        return;
      default: {
        const never: never = r;
        return never;
      }
    }
  };
  await bridge.subscribe(topics.jointTrajectory, 'joint_trajectory', onTrajectory);
  o.onInfo(
    `${o.armId} in ROS 2 (domain ${bridge.domain}): ${topics.jointStates}, ${topics.robotDescription}, ${topics.jointTrajectory}`,
  );

  let stopping = false;
  const lost = bridge.exited.then((code) =>
    stopping ? '' : `the ROS 2 bridge process exited (${code})`,
  );
  return {
    topics,
    counts,
    lost,
    bridge,
    mqtt,
    claims,
    async stop() {
      stopping = true;
      streamer.cancel();
      claims.release();
      await mqtt.endAsync();
      await bridge.close();
    },
  };
}
