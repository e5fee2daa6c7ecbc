import { Option, type Command } from 'commander';
import {
  BUS_MODELS_DIR,
  DEFAULT_BUS_GATEWAY_OPTIONS,
  DEFAULT_GATEWAY_OPTIONS,
  formatDoctorReport,
  loadProfile,
  runBusDoctor,
  startBusGateway,
  startGateway,
  startLeaderGateway,
} from '@armtwin/gateway';
import { BUS_PROTOCOLS, type BusProtocol } from '@armtwin/servo-bus';
import { DEFAULT_ROS2_GATEWAY_START, MAX_ROS2_DOMAIN, startRos2Gateway } from '@armtwin/ros2';
import { DEFAULT_PROFILE } from '@armtwin/sim';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { armId, number, operatorLeaseOption } from './options.ts';
import { untilSignal } from './signals.ts';

interface GatewayFlags {
  serial?: string;
  ros2?: boolean;
  jointStates: string;
  trajectory: string;
  domain?: number;
  baud?: number;
  bus: 'lsc' | BusProtocol;
  profile: string;
  models: string;
  rate: number;
  healthRate: number;
  mqtt?: string;
  arm: string;
  username?: string;
  password?: string;
  operatorLease: number;
  doctor: boolean;
  leaderOf?: string;
  user: string;
}

export function registerGateway(program: Command): void {
  program
    .command('gateway')
    .description(
      'bridge a real controller on a serial line to MQTT (status ← serial, control → serial)',
    )
    .option('--serial <path>', 'serial device, e.g. /dev/ttyUSB0 (or --ros2)')
    .option('--ros2', 'the arm is a ROS 2 arm: joint states in, JointTrajectory out (docs/ros2.md)')
    .option(
      '--joint-states <topic>',
      "ROS 2: the arm's sensor_msgs/JointState topic",
      DEFAULT_ROS2_GATEWAY_START.jointStates,
    )
    .option(
      '--trajectory <topic>',
      "ROS 2: its joint trajectory controller's trajectory_msgs/JointTrajectory topic",
      DEFAULT_ROS2_GATEWAY_START.trajectory,
    )
    .option(
      '--domain <id>',
      "ROS 2: ROS_DOMAIN_ID (default: the environment's, else 0)",
      number('domain', 0, MAX_ROS2_DOMAIN, true),
    )
    .option(
      '--baud <rate>',
      `baud rate (default ${DEFAULT_GATEWAY_OPTIONS.baudRate}; on a servo bus ${DEFAULT_BUS_GATEWAY_OPTIONS.baudRate})`,
      number('baud', 300, 4_000_000, true),
    )
    .addOption(
      new Option(
        '--bus <kind>',
        'what is on the line: lsc (a controller speaking frames) or a servo bus',
      )
        .choices(['lsc', ...BUS_PROTOCOLS])
        .default('lsc'),
    )
    .option(
      '--profile <name>',
      'robot profile (ids, limits, keep-out zones, IK) of the arm on the line',
      DEFAULT_PROFILE,
    )
    .option('--models <dir>', 'the folder of robot profiles', BUS_MODELS_DIR)
    .option(
      '--rate <hz>',
      'servo bus: positions read per second',
      number('rate', 1, 1000),
      DEFAULT_BUS_GATEWAY_OPTIONS.stateRate,
    )
    .option(
      '--health-rate <hz>',
      'servo bus: temperatures and voltages read per second',
      number('health rate', 0.1, 100),
      DEFAULT_BUS_GATEWAY_OPTIONS.healthRate,
    )
    .option(
      '--mqtt <urls>',
      'broker URL, or an ordered comma-separated list: the first preferred, the rest fall-backs (env MQTT_URL)',
    )
    .option('--arm <id>', 'arm id', armId, 'arm1')
    .option('--username <name>', 'broker user name (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .addOption(operatorLeaseOption())
    .option(
      '--leader-of <arm>',
      'servo bus: the bus holds a leader arm (torque off, moved by hand) whose pose drives this follower arm through its controller',
      armId,
    )
    .option(
      '--user <name>',
      "--leader-of: who the leader is to the follower's controller (its lease and commands)",
      'leader',
    )
    .option(
      '--doctor',
      'servo bus: scan every baud rate and id, report what is wrong and how to fix it, and exit (1 when an error is found)',
      false,
    )
    .addHelpText(
      'after',
      `
Serial bytes are cut into frames, re-encoded and published on arm/{id}/status, one payload per
serial read, stamped $TIM (the device's own $TIM frames are dropped). Payloads on arm/{id}/control
are checked by the controller core against --profile (limits, floor, keep-out zones,
self-collision, rate limit, payload bound; $KMS through its IK) as on the simulator: a refused one
is answered $ERR on status and never reaches the board; what passes is written to the line as
timed moves (a group as one {...} group), reads and pings as they came. While the line is down
commands are answered $ERR:gateway: serial line down!. arm/{id}/online is 1 (retained) while the
line is open and the broker connected, 0 otherwise (also the last will). Deadman: a 0 on
arm/{id}/operator, or an operator that repeated 1 and then fell silent for --operator-lease ms,
writes #255PDST! to the line while the arm moves. The port is reopened with back-off (250 ms
doubling to 5 s) and the broker reconnected every second.

With --bus dynamixel|feetech the gateway drives the profile's servos itself (docs/arm-side.md):
it pings their ids at start ($ERR for missing ones), reads positions by sync read at --rate and
publishes them as angle frames #IIIA±ddd.dd!, temperature and voltage at --health-rate as
#IIITtttVvvvv!; pulse and angle moves are checked against the profile's limits and written by
sync write at the speed their T asks; #IIIPDST!/#255PDST! and the deadman hold position. Torque
is on at start; 0 on arm/{id}/torque turns it off, 1 back on. $KMS goes through the profile's IK.
Before it starts, the servo doctor checks the bus at --baud (ids, model, firmware, supply against
the servos' voltage, overheat and overload flags...) and logs each finding with its fix; with
--doctor it also tries every baud rate, prints the report and exits (docs/so101.md).

With --leader-of ARM the bus holds a leader arm (an SO-101 leader: same servo names as its
follower): torque goes off, its positions are read at --rate and announced on
arm/ARM/leader/USER ($TIM + angle frames, for the HUD's ghost), and each pose that moved goes to
ARM as USER's angle moves (--user, default leader) on arm/ARM/control/USER, holding ARM's lease:
ARM's controller checks limits and keep-out zones. After an emergency stop (or a lost lease) the
leader stops driving ARM until 1 is published on arm/ARM/leader/USER/enable; whether it follows is
retained on arm/ARM/leader/USER/state (docs/so101.md).

With --ros2 (needs bash scripts/install-ros2.sh once) the arm is a ROS 2 arm, e.g. under
ros2_control: its joint states (matched to --profile by joint name) are published as angle frames
at --rate, and every command (jog, $KMS, plans, motion requests) is checked by the controller
core and sent as a JointTrajectory; a stop, the e-stop and the deadman send one that holds where
the joints are. The arm is offline while no joint state arrives.`,
    )
    .action(async (flags: GatewayFlags) => {
      if (!flags.serial && !flags.ros2) program.error('gateway needs --serial <path> or --ros2');
      const env = loadCliConfig();
      const log = createLogger('gateway', env.logLevel);
      const username = flags.username ?? env.mqttUsername;
      const line = {
        serialPath: flags.serial ?? '',
        mqttUrl: flags.mqtt ?? env.mqttUrl,
        armId: flags.arm,
        operatorLeaseMs: flags.operatorLease,
        ...(username ? { username, password: flags.password ?? env.mqttPassword } : {}),
        onFirst: firstOnly(log),
        log,
      };
      if (!flags.ros2 && flags.bus !== 'lsc') {
        const baudRate = flags.baud ?? DEFAULT_BUS_GATEWAY_OPTIONS.baudRate;
        const ids = loadProfile(flags.profile, flags.models).profile.servos.map((s) => s.id);
        const doctor = { bus: flags.bus, serialPath: line.serialPath, baudRate, ids };
        if (flags.doctor) {
          const report = await runBusDoctor({ ...doctor, allBauds: true });
          process.stdout.write(formatDoctorReport(report));
          process.exitCode = report.findings.some((f) => f.severity === 'error') ? 1 : 0;
          return;
        }
        try {
          const report = await runBusDoctor({ ...doctor, allBauds: false });
          for (const f of report.findings)
            log.warn(`servo doctor: [${f.kind}] ${f.finding}; fix: ${f.fix}`);
        } catch (err) {
          log.warn(`servo doctor: could not check the bus (${(err as Error).message})`);
        }
      }
      if (flags.leaderOf) {
        if (flags.ros2 || flags.bus === 'lsc')
          program.error('--leader-of needs a servo bus: --bus feetech|dynamixel --serial <path>');
        const leader = startLeaderGateway({
          ...line,
          bus: flags.bus,
          profile: flags.profile,
          modelsDir: flags.models,
          follower: flags.leaderOf,
          user: flags.user,
          stateRate: flags.rate,
          baudRate: flags.baud ?? DEFAULT_BUS_GATEWAY_OPTIONS.baudRate,
        });
        await untilSignal(log);
        await leader.stop();
        return;
      }
      const gw = flags.ros2
        ? await startRos2Gateway({
            ...line,
            profile: flags.profile,
            modelsDir: flags.models,
            jointStates: flags.jointStates,
            trajectory: flags.trajectory,
            domain: flags.domain,
            stateRate: flags.rate,
          })
        : flags.bus === 'lsc'
          ? startGateway({
              ...line,
              profile: flags.profile,
              modelsDir: flags.models,
              baudRate: flags.baud ?? DEFAULT_GATEWAY_OPTIONS.baudRate,
            })
          : startBusGateway({
              ...line,
              bus: flags.bus,
              profile: flags.profile,
              modelsDir: flags.models,
              stateRate: flags.rate,
              healthRate: flags.healthRate,
              baudRate: flags.baud ?? DEFAULT_BUS_GATEWAY_OPTIONS.baudRate,
            });
      const lost = await Promise.race([
        untilSignal(log).then(() => ''),
        'lost' in gw ? gw.lost : new Promise<string>(() => {}),
      ]);
      await gw.stop();
      if (lost) {
        log.error(lost);
        process.exitCode = 1;
      }
    });
}
