/**
 * Wires `armtwin gateway --ros2`: the robot profile from disk (announced retained on
 * `arm/{id}/profile` and its file followed, as the bus gateway does: @armtwin/gateway's
 * `followProfile`, so zones and limits saved from the HUD are in force without a restart), the
 * rclpy bridge process (the
 * arm's joint states in, trajectories out), the gateway's MQTT client (last will `0` on
 * `arm/{id}/online`, the control arbiter: @armtwin/gateway), `Ros2GatewayCore` and motion
 * requests (@armtwin/controller), on the system clock. Resolves once the arm's first joint state
 * has every profile joint; throws, naming what is missing, if it does not.
 */
import type { MqttClient } from 'mqtt';
import { MotionRequests, numericKms, zonesKeepOut } from '@armtwin/controller';
import { armSummary, startMotionService } from '@armtwin/controller/mqtt';
import {
  connectGatewayMqtt,
  DEFAULT_GATEWAY_OPTIONS,
  followProfile,
  gatewayPublish,
  leaveGatewayMqtt,
  wireGatewayMqtt,
  type GatewayOptions,
} from '@armtwin/gateway';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { armTopics, SYSTEM_CLOCK } from '@armtwin/protocol';
import { Ros2Bridge } from '../bridge-process.ts';
import type { JointStateMsg } from '../wire.ts';
import { DEFAULT_ROS2_GATEWAY_OPTIONS, Ros2GatewayCore } from './ros2-gateway-core.ts';

export interface Ros2GatewayStartOptions extends Pick<
  GatewayOptions,
  'mqttUrl' | 'armId' | 'username' | 'password' | 'onFirst' | 'log' | 'operatorLeaseMs'
> {
  profile: string;
  modelsDir: string;
  /** The arm's JointState topic. */
  jointStates: string;
  /** Its joint trajectory controller's command topic. */
  trajectory: string;
  /** ROS_DOMAIN_ID; undefined: the environment's, else 0. */
  domain: number | undefined;
  stateRate: number;
  staleMs: number;
  /** Longest wait for the arm's first joint state, ms. */
  firstStateMs: number;
  env: NodeJS.ProcessEnv;
}

export const DEFAULT_ROS2_GATEWAY_START = {
  modelsDir: MODELS_DIR,
  jointStates: '/joint_states',
  trajectory: '/joint_trajectory_controller/joint_trajectory',
  domain: undefined,
  stateRate: DEFAULT_ROS2_GATEWAY_OPTIONS.stateRate,
  staleMs: DEFAULT_ROS2_GATEWAY_OPTIONS.staleMs,
  firstStateMs: 30_000,
  env: process.env,
} satisfies Partial<Ros2GatewayStartOptions>;

export interface Ros2Gateway {
  core: Ros2GatewayCore;
  client: MqttClient;
  bridge: Ros2Bridge;
  /** Resolves with the reason if the rclpy process ends before `stop()` (the arm is then offline). */
  lost: Promise<string>;
  stop(): Promise<void>;
}

export async function startRos2Gateway(
  options: Partial<Ros2GatewayStartOptions> &
    Pick<Ros2GatewayStartOptions, 'mqttUrl' | 'armId' | 'profile'>,
): Promise<Ros2Gateway> {
  const o = { ...DEFAULT_GATEWAY_OPTIONS, ...DEFAULT_ROS2_GATEWAY_START, ...options };
  const { log } = o;
  const { profile, robot, raw } = readRobotFolder(o.profile, o.modelsDir);
  const bridge = await Ros2Bridge.start({
    domain: o.domain,
    nodeName: `armtwin_gateway_${o.armId.replace(/-/g, '_')}`,
    env: o.env,
    onError: (kind, message) => o.onFirst(`ros2-${kind}`, `ROS 2 bridge: ${message}`),
  });
  const first = new Promise<JointStateMsg>((resolve) => {
    void bridge.subscribe(o.jointStates, 'joint_state', resolve);
  });
  let timer: ReturnType<typeof setTimeout> | undefined;
  const firstState = await Promise.race([
    first,
    new Promise<undefined>(
      (resolve) => (timer = setTimeout(() => resolve(undefined), o.firstStateMs)),
    ),
  ]);
  clearTimeout(timer);
  const missing = firstState
    ? profile.servos.filter((s) => !firstState.name.includes(s.joint)).map((s) => s.joint)
    : [];
  if (!firstState || missing.length) {
    await bridge.close();
    throw new Error(
      firstState
        ? `${o.jointStates} has no joint ${missing.join(', ')} of profile ${profile.name} (it has ${firstState.name.join(', ')})`
        : `no joint state on ${o.jointStates} in ${o.firstStateMs} ms (ROS domain ${bridge.domain})`,
    );
  }

  await bridge.advertise(o.trajectory, 'joint_trajectory', { waitMs: 5000 });
  const topics = armTopics(o.armId);
  const client = connectGatewayMqtt({ ...o, serialPath: '', serial: {} });
  const summary = armSummary(client, o.armId, SYSTEM_CLOCK);
  const core = new Ros2GatewayCore(
    {
      armId: o.armId,
      profile,
      stateRate: o.stateRate,
      staleMs: o.staleMs,
      operatorLeaseMs: o.operatorLeaseMs,
      kms: numericKms(robot),
      keepOut: zonesKeepOut(robot),
      robot,
    },
    {
      ...SYSTEM_CLOCK,
      publish: gatewayPublish(client, summary),
      trajectory: (msg) => bridge.publish(o.trajectory, 'joint_trajectory', msg),
      onFirst: o.onFirst,
    },
  );
  // No await from the client's creation to its wiring: its first connect must not be missed.
  const control = wireGatewayMqtt(client, o, core);
  const follow = followProfile({
    ...o,
    client,
    name: o.profile,
    raw,
    core,
    onReload: (name) =>
      log?.info({ profile: name }, 'profile file changed: new limits and zones in force'),
  });
  core.fromJointState(firstState);
  const motion = startMotionService(
    client,
    new MotionRequests(core.controller, () => core.robot ?? robot, SYSTEM_CLOCK.now(), {
      mayExecute: (user) => control.refusal(user, 'a motion request on the arm'),
      onFirst: o.onFirst,
      controlTopic: topics.control,
    }),
    o.armId,
    SYSTEM_CLOCK,
    o.onFirst,
  );
  core.start();
  summary.start(
    () => core.controller,
    () => control.holder,
  );
  await bridge.subscribe(o.jointStates, 'joint_state', (msg) => core.fromJointState(msg));
  log?.info(
    {
      arm: o.armId,
      profile: profile.name,
      jointStates: o.jointStates,
      trajectory: o.trajectory,
      domain: bridge.domain,
    },
    'ROS 2 gateway running',
  );
  let stopping = false;
  return {
    core,
    client,
    bridge,
    lost: bridge.exited.then((code) =>
      stopping ? '' : `the ROS 2 bridge process exited (${code})`,
    ),
    async stop() {
      stopping = true;
      motion.stop();
      follow.stop();
      core.stop();
      control.reset();
      await summary.stop();
      await leaveGatewayMqtt(client, o.armId);
      await bridge.close();
      log?.info({ counters: core.counters, bridge: bridge.errors }, 'gateway stopped');
    },
  };
}
