/** `armtwin ros2` (./arm-in-ros.ts): its settings and their defaults, declared once. */
import type { Clock } from '@armtwin/protocol';
import { SYSTEM_CLOCK } from '@armtwin/protocol';

export interface ArmInRosOptions {
  /** Broker URL, or an ordered comma-separated list (docs/protocol.md § Several brokers). */
  mqttUrl: string;
  username: string | undefined;
  password: string | undefined;
  /** The armtwin arm shown in ROS 2. */
  armId: string;
  /** Its robot profile (`<modelsDir>/<profile>/profile.json` and its URDF). */
  profile: string;
  /** The folder of robot profiles; undefined: armtwin's own `public/models`. */
  modelsDir: string | undefined;
  /** Who the bridge is on MQTT: it commands on `arm/{id}/control/{user}`, claims on `…/claim/{user}`. */
  user: string;
  /** Take control of the arm at start (when nobody holds it) and keep the lease while running. */
  take: boolean;
  /** ROS_DOMAIN_ID; undefined: the environment's, else 0. */
  domain: number | undefined;
  /** The ROS 2 namespace of the arm's topics; undefined: `/armtwin/<armId>`. */
  namespace: string | undefined;
  /** A trajectory is streamed as one frame group every stepMs, ms. */
  stepMs: number;
  /** Told the first time each kind of problem happens (later ones are only counted). */
  onFirst: (kind: string, message: string) => void;
  /** Told of what happens once: started, a trajectory taken, control taken or lost. */
  onInfo: (message: string) => void;
  clock: Clock;
  /** The environment the ROS 2 venv is found with. */
  env: NodeJS.ProcessEnv;
}

export const DEFAULT_ARM_IN_ROS_OPTIONS: ArmInRosOptions = {
  mqttUrl: 'mqtt://localhost:1883',
  username: undefined,
  password: undefined,
  armId: 'arm1',
  profile: 'armtwin5',
  modelsDir: undefined,
  user: 'ros2',
  take: false,
  domain: undefined,
  namespace: undefined,
  stepMs: 100,
  onFirst: () => {},
  onInfo: () => {},
  clock: SYSTEM_CLOCK,
  env: process.env,
};

/**
 * The arm's id as one ROS 2 name token: `-` is not allowed there (it becomes `_`), nor a leading
 * digit (`arm_` is put in front).
 */
export const rosToken = (armId: string): string =>
  (/^[0-9]/.test(armId) ? `arm_${armId}` : armId).replace(/-/g, '_');

/** The ROS 2 topics of an arm under its namespace (default `/armtwin/<arm>`). */
export function armRosTopics(armId: string, namespace?: string) {
  const ns = (namespace ?? `/armtwin/${rosToken(armId)}`).replace(/\/+$/, '');
  return {
    jointStates: `${ns}/joint_states`,
    robotDescription: `${ns}/robot_description`,
    jointTrajectory: `${ns}/joint_trajectory`,
  };
}
