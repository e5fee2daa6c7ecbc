import { Option, type Command } from 'commander';
import {
  DEFAULT_SIM_OPTIONS,
  MAX_STATE_RATE,
  REPORT_UNITS,
  startSim,
  type Fault,
  type ReportUnits,
} from '@armtwin/sim';
import {
  BUS_PROTOCOLS,
  parseBenchFault,
  type BenchFault,
  type BusProtocol,
} from '@armtwin/servo-bus';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { armId, number, operatorLeaseOption } from './options.ts';
import { untilSignal } from './signals.ts';

const servo = number('servo id', 0, 254, true);
const collect =
  <T>(parse: (v: string) => T) =>
  (value: string, previous: T[] = []) => [...previous, parse(value)];

function overheat(value: string): Fault {
  const [id = '', celsius] = value.split(':');
  return {
    fault: 'overheat',
    id: servo(id),
    ...(celsius ? { celsius: number('°C', 0, 999)(celsius) } : {}),
  };
}

interface SimFlags {
  mqtt?: string;
  arm: string;
  profile: string;
  models: string;
  report: ReportUnits;
  thermalTimeScale: number;
  rate: number;
  healthRate: number;
  username?: string;
  password?: string;
  serial?: string;
  baud: number;
  bus?: BusProtocol;
  busFault?: BenchFault[];
  hand: boolean;
  stall?: number[];
  overheat?: Fault[];
  undervolt?: number;
  drop?: number;
  latency?: number;
  operatorLease: number;
}

/** The fault flags, in the order the help lists them. */
function faultsFrom(flags: SimFlags): Fault[] {
  return [
    ...(flags.stall ?? []).map((id): Fault => ({ fault: 'stall', id })),
    ...(flags.overheat ?? []),
    ...(flags.undervolt !== undefined
      ? [{ fault: 'undervolt', mv: flags.undervolt } as Fault]
      : []),
    ...(flags.drop !== undefined ? [{ fault: 'drop', percent: flags.drop } as Fault] : []),
    ...(flags.latency !== undefined ? [{ fault: 'latency', ms: flags.latency } as Fault] : []),
  ];
}

const FAULT_HELP = `
Fault injection (flags at start; at runtime publish JSON on arm/{id}/sim, one object or an array;
the faults in force are published retained on arm/{id}/sim/faults):
  {"fault":"stall","id":1}                  servo 001 jams where it is, pushes and heats
  {"fault":"overheat","id":2,"celsius":85}  servo 002 heats towards 85 °C (default 85)
  {"fault":"undervolt","mv":6200}           supply limited to 6200 mV (0 = off)
  {"fault":"drop","percent":20}             drop 20 % of state samples (0 = off)
  {"fault":"latency","ms":50}               delay payloads out and commands in by 50 ms each
                                            (#255PDST! still acts at once and discards the queue)
  {"fault":"clear","id":2}  /  {"fault":"clear"}   clear one servo's faults / every fault
Example: mosquitto_pub -t arm/arm1/sim -m '{"fault":"overheat","id":2}'`;

const MOTION_HELP = `

Motion requests (docs/protocol.md "Motion requests"): JSON on arm/{id}/request, answers on
arm/{id}/feedback; the profile is announced retained on arm/{id}/profile.
Example: mosquitto_pub -t arm/arm1/request -m '{"id":"r1","mode":"joint","targets":["ready"],"execute":true}'`;

export function registerSim(program: Command): void {
  const d = DEFAULT_SIM_OPTIONS;
  program
    .command('sim')
    .description(
      'run a simulated arm controller that behaves like the firmware (MQTT, or a serial line)',
    )
    .option(
      '--mqtt <urls>',
      'broker URL, or an ordered comma-separated list: the first preferred, the rest fall-backs (env MQTT_URL)',
    )
    .option('--arm <id>', 'arm id', armId, 'arm1')
    .option(
      '--profile <name>',
      'robot profile: public/models/<name>/profile.json (announced on arm/{id}/profile)',
      d.profile,
    )
    .addOption(
      new Option('--models <dir>', 'the folder of robot profiles').default(
        d.modelsDir,
        'public/models',
      ),
    )
    .addOption(
      new Option(
        '--report <units>',
        'position reports: as the profile says, all angle frames #IIIA±ddd.dd! (PROTOCOL §8), or all pulse widths',
      )
        .choices(REPORT_UNITS)
        .default(d.report),
    )
    .option(
      '--rate <hz>',
      `state rate, Hz (max ${MAX_STATE_RATE})`,
      number('rate', 1, MAX_STATE_RATE),
      d.rate,
    )
    .option(
      '--thermal-time-scale <k>',
      'heat runs k times faster than the clock (tests, demos: no waiting minutes for a servo to warm)',
      number('thermal time scale', 0.01, 1000),
      d.thermalTimeScale,
    )
    .option('--health-rate <hz>', 'health rate, Hz', number('health rate', 0.1, 100), d.healthRate)
    .option('--username <name>', 'broker user name (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .addOption(
      new Option(
        '--serial <path>',
        'speak on this serial line instead of MQTT (no $TIM, no presence)',
      ),
    )
    .option('--baud <rate>', 'serial baud rate', number('baud', 300, 4_000_000, true), d.baudRate)
    .addOption(
      new Option(
        '--bus <protocol>',
        "with --serial: answer as a servo bus of the profile's servos (ids from the profile) instead of frames",
      ).choices(BUS_PROTOCOLS),
    )
    .option(
      '--hand',
      'with --bus: read hand moves from stdin, one line each: ID:DEGREES[,ID:DEGREES…] puts the shafts there (a leader arm, torque off)',
      false,
    )
    .option('--stall <id>', 'stall this servo (repeatable)', collect(servo))
    .option(
      '--bus-fault <fault>',
      'with --bus: a fault of the bench, absent:ID, extra:ID, clash:ID or field:ID:FIELD=VALUE (repeatable; e.g. field:2:maxVoltageLimit=80)',
      collect(parseBenchFault),
    )
    .option('--overheat <id[:celsius]>', 'overheat this servo (repeatable)', collect(overheat))
    .option(
      '--undervolt <mv>',
      'limit the supply to this many mV',
      number('undervolt', 0, 9999, true),
    )
    .option('--drop <percent>', 'drop this percentage of state samples', number('drop', 0, 100))
    .option(
      '--latency <ms>',
      'delay every payload and command by this many ms',
      number('latency', 0, 60000, true),
    )
    .addOption(operatorLeaseOption())
    .addHelpText('after', FAULT_HELP + MOTION_HELP)
    .action(async (flags: SimFlags) => {
      if (flags.bus && !flags.serial) program.error('--bus needs --serial <path>');
      if (flags.hand && !flags.bus) program.error('--hand needs --bus <protocol>');
      const env = loadCliConfig();
      const log = createLogger('sim', env.logLevel);
      const sim = await startSim({
        mqttUrl: flags.mqtt ?? env.mqttUrl,
        username: flags.username ?? env.mqttUsername,
        password: flags.password ?? env.mqttPassword,
        armId: flags.arm,
        profile: flags.profile,
        modelsDir: flags.models,
        report: flags.report,
        thermalTimeScale: flags.thermalTimeScale,
        rate: flags.rate,
        healthRate: flags.healthRate,
        serialPath: flags.serial ?? '',
        baudRate: flags.baud,
        bus: flags.bus ?? '',
        faults: faultsFrom(flags),
        benchFaults: flags.busFault ?? [],
        operatorLeaseMs: flags.operatorLease,
        ...(flags.hand ? { handInput: process.stdin } : {}),
        log,
        onFirst: firstOnly(log),
      });
      const lost = await Promise.race([untilSignal(log).then(() => ''), sim.closed]);
      await sim.stop();
      if (lost) {
        log.error({ reason: lost }, 'serial line closed');
        process.exitCode = 1;
      }
    });
}
