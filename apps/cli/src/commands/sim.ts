import { InvalidArgumentError, Option, type Command } from 'commander';
import mqtt from 'mqtt';
import { isValidArmId, OPERATOR_LEASE_MS } from '@armtwin/protocol';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import type { Fault } from '../sim/faults.ts';
import { simWill, startMqttSim } from '../sim/mqtt-sim.ts';
import { DEFAULT_PROFILE, loadSimProfile } from '../sim/profile.ts';
import { MAX_STATE_RATE } from '../sim/runner.ts';
import { startSerialSim } from '../sim/serial-sim.ts';
import { untilSignal } from './signals.ts';

export const number =
  (name: string, min: number, max: number, integer = false) =>
  (value: string): number => {
    const n = Number(value);
    if (
      value.trim() === '' ||
      !Number.isFinite(n) ||
      n < min ||
      n > max ||
      (integer && !Number.isInteger(n))
    ) {
      throw new InvalidArgumentError(
        `${name} must be ${integer ? 'an integer' : 'a number'} in ${min}–${max}`,
      );
    }
    return n;
  };

export const armId = (value: string): string => {
  if (!isValidArmId(value)) throw new InvalidArgumentError('arm id must match [a-z0-9-]{1,32}');
  return value;
};

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
  mqtt: string;
  arm: string;
  profile: string;
  rate: number;
  healthRate: number;
  username?: string;
  password?: string;
  serial?: string;
  baud: number;
  stall?: number[];
  overheat?: Fault[];
  undervolt?: number;
  drop?: number;
  latency?: number;
  operatorLease: number;
}

/** `--operator-lease <ms>`, shared by sim and gateway. */
export const operatorLeaseOption = () =>
  new Option(
    '--operator-lease <ms>',
    'let a beating operator go after this long without a 1 on arm/{id}/operator (0 = only its 0)',
  )
    .argParser(number('operator lease', 0, 600_000, true))
    .default(OPERATOR_LEASE_MS);

export const FAULT_HELP = `
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

export const MOTION_HELP = `

Motion requests (docs/protocol.md "Motion requests"): JSON on arm/{id}/request, answers on
arm/{id}/feedback; the profile is announced retained on arm/{id}/profile.
Example: mosquitto_pub -t arm/arm1/request -m '{"id":"r1","mode":"joint","targets":["ready"],"execute":true}'`;

export function registerSim(program: Command): void {
  program
    .command('sim')
    .description(
      'run a simulated arm controller that behaves like the firmware (MQTT, or a serial line)',
    )
    .option('--mqtt <url>', 'broker URL (env MQTT_URL)')
    .option('--arm <id>', 'arm id', armId, 'arm1')
    .option(
      '--profile <name>',
      'robot profile: public/models/<name>/profile.json (announced on arm/{id}/profile)',
      DEFAULT_PROFILE,
    )
    .option(
      '--rate <hz>',
      `state rate, Hz (max ${MAX_STATE_RATE})`,
      number('rate', 1, MAX_STATE_RATE),
      50,
    )
    .option('--health-rate <hz>', 'health rate, Hz', number('health rate', 0.1, 100), 2)
    .option('--username <name>', 'broker user name (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .addOption(
      new Option(
        '--serial <path>',
        'speak on this serial line instead of MQTT (no $TIM, no presence)',
      ),
    )
    .option('--baud <rate>', 'serial baud rate', number('baud', 300, 4_000_000, true), 115200)
    .option('--stall <id>', 'stall this servo (repeatable)', collect(servo))
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
      const env = loadCliConfig();
      const log = createLogger('sim', env.logLevel);
      const faults: Fault[] = [
        ...(flags.stall ?? []).map((id): Fault => ({ fault: 'stall', id })),
        ...(flags.overheat ?? []),
        ...(flags.undervolt !== undefined
          ? [{ fault: 'undervolt', mv: flags.undervolt } as Fault]
          : []),
        ...(flags.drop !== undefined ? [{ fault: 'drop', percent: flags.drop } as Fault] : []),
        ...(flags.latency !== undefined ? [{ fault: 'latency', ms: flags.latency } as Fault] : []),
      ];
      const profile = loadSimProfile(flags.profile);
      const runnerOptions = {
        model: profile.model,
        rate: flags.rate,
        healthRate: flags.healthRate,
        faults,
        onFirst: firstOnly(log),
      };
      if (flags.serial) {
        const sim = await startSerialSim({
          ...runnerOptions,
          path: flags.serial,
          baudRate: flags.baud,
        });
        log.info(
          { serial: flags.serial, rate: flags.rate },
          'simulated controller on the serial line',
        );
        const lost = await Promise.race([untilSignal(log).then(() => ''), sim.closed]);
        await sim.stop();
        if (lost) {
          log.error({ reason: lost }, 'serial line closed');
          process.exitCode = 1;
        }
        return;
      }
      const url = flags.mqtt ?? env.mqttUrl;
      const username = flags.username ?? env.mqttUsername;
      const password = flags.password ?? env.mqttPassword;
      const client = mqtt.connect(url, {
        clientId: `armtwin-sim-${flags.arm}-${process.pid}`,
        ...(username ? { username, password } : {}),
        will: simWill(flags.arm),
        keepalive: 60,
        reconnectPeriod: 1000,
        queueQoSZero: false,
      });
      client.on('connect', () => {
        // Frames are small: don't let Nagle's algorithm hold them back (~40 ms tails otherwise).
        (client.stream as { setNoDelay?: (on: boolean) => void } | undefined)?.setNoDelay?.(true);
        log.info({ url, arm: flags.arm }, 'connected');
      });
      client.on('error', (err) => log.warn({ err: err.message }, 'mqtt error'));
      const sim = startMqttSim(client, {
        ...runnerOptions,
        armId: flags.arm,
        profile,
        operatorLeaseMs: flags.operatorLease,
      });
      log.info(
        {
          arm: flags.arm,
          profile: flags.profile,
          rate: flags.rate,
          healthRate: flags.healthRate,
          faults: sim.runner.faults,
        },
        'sim running',
      );
      await untilSignal(log);
      await sim.stop();
      log.info({ counters: sim.runner.counters, model: sim.runner.model.counters }, 'sim stopped');
    });
}
