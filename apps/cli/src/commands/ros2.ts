import { InvalidArgumentError, Option, type Command } from 'commander';
import { CONTROL_USER_PATTERN } from '@armtwin/protocol';
import { DEFAULT_ARM_IN_ROS_OPTIONS, MAX_ROS2_DOMAIN, startArmInRos } from '@armtwin/ros2';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { armId, number } from './options.ts';
import { untilSignal } from './signals.ts';

interface Ros2Flags {
  mqtt?: string;
  arm: string;
  profile: string;
  models?: string;
  user: string;
  take?: boolean;
  domain?: number;
  namespace?: string;
  stepMs: number;
  username?: string;
  password?: string;
}

const controlUser = (value: string): string => {
  if (!CONTROL_USER_PATTERN.test(value))
    throw new InvalidArgumentError(`user must match ${CONTROL_USER_PATTERN.source}`);
  return value;
};

const HELP = `
Needs ROS 2 once per machine: bash scripts/install-ros2.sh (rclpy and FastDDS wheels, cached).
ROS 2 topics (namespace /armtwin/<arm>, a '-' in the id becomes '_'):
  joint_states        sensor_msgs/JointState, radians (metres for a prismatic axis), URDF joint names
  robot_description   std_msgs/String, the profile's URDF, transient local (latched)
  joint_trajectory    trajectory_msgs/JointTrajectory in: moves the arm through the lease, as the
                      user --user (a non-holder's trajectory is refused by the controller);
                      an empty one stops the joints it names
Example: npx armtwin ros2 --arm arm1 --take
         ros2 topic echo /armtwin/arm1/joint_states   (on a machine with ROS 2, same domain)
Docs: docs/ros2.md`;

export function registerRos2(program: Command): void {
  const d = DEFAULT_ARM_IN_ROS_OPTIONS;
  program
    .command('ros2')
    .description(
      'show an armtwin arm in ROS 2: joint_states, robot_description and a JointTrajectory input',
    )
    .option('--mqtt <urls>', 'broker URL, or an ordered comma-separated list (env MQTT_URL)')
    .option('--arm <id>', 'arm id', armId, d.armId)
    .option('--profile <name>', "the arm's robot profile (public/models/<name>)", d.profile)
    .option('--models <dir>', 'the folder of robot profiles (default public/models)')
    .option(
      '--user <name>',
      'who the bridge is on MQTT (its control and claim topics)',
      controlUser,
      d.user,
    )
    .option('--take', 'hold the arm whenever nobody else does, beating to keep the lease')
    .option(
      '--domain <id>',
      "ROS_DOMAIN_ID (default: the environment's, else 0)",
      number('domain', 0, MAX_ROS2_DOMAIN, true),
    )
    .option('--namespace <ns>', 'ROS 2 namespace of the topics (default /armtwin/<arm>)')
    .addOption(
      new Option('--step-ms <ms>', 'a trajectory is streamed as one frame group every ms')
        .argParser(number('step', 20, 1000, true))
        .default(d.stepMs),
    )
    .option('--username <name>', 'broker user name (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .addHelpText('after', HELP)
    .action(async (flags: Ros2Flags) => {
      const env = loadCliConfig();
      const log = createLogger('ros2', env.logLevel);
      const arm = await startArmInRos({
        mqttUrl: flags.mqtt ?? env.mqttUrl,
        username: flags.username ?? (env.mqttUsername || undefined),
        password: flags.password ?? (env.mqttPassword || undefined),
        armId: flags.arm,
        profile: flags.profile,
        modelsDir: flags.models,
        user: flags.user,
        take: flags.take === true,
        domain: flags.domain,
        namespace: flags.namespace,
        stepMs: flags.stepMs,
        onFirst: firstOnly(log),
        onInfo: (message) => log.info(message),
      });
      const lost = await Promise.race([untilSignal(log).then(() => ''), arm.lost]);
      await arm.stop();
      log.info({ ...arm.counts, bridgeErrors: arm.bridge.errors }, 'stopped');
      if (lost) {
        log.error(lost);
        process.exitCode = 1;
      }
    });
}
