import type { Command } from 'commander';
import { loadCliConfig } from '../config.ts';
import { startGateway } from '../gateway/start-gateway.ts';
import { createLogger, firstOnly } from '../log.ts';
import { untilSignal } from './signals.ts';
import { armId, number, operatorLeaseOption } from './sim.ts';

interface GatewayFlags {
  serial: string;
  baud: number;
  mqtt?: string;
  arm: string;
  username?: string;
  password?: string;
  operatorLease: number;
}

export function registerGateway(program: Command): void {
  program
    .command('gateway')
    .description(
      'bridge a real controller on a serial line to MQTT (status ← serial, control → serial)',
    )
    .requiredOption('--serial <path>', 'serial device, e.g. /dev/ttyUSB0')
    .option('--baud <rate>', 'baud rate', number('baud', 300, 4_000_000, true), 115200)
    .option('--mqtt <url>', 'broker URL (env MQTT_URL)')
    .option('--arm <id>', 'arm id', armId, 'arm1')
    .option('--username <name>', 'broker user name (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .addOption(operatorLeaseOption())
    .addHelpText(
      'after',
      `
Serial bytes are cut into frames, re-encoded and published on arm/{id}/status, one payload per
serial read, stamped $TIM (the device's own $TIM frames are dropped). Payloads on arm/{id}/control
are written to the line verbatim; while the line is down they are dropped and answered with
$ERR:gateway: serial line down! on status. arm/{id}/online is 1 (retained) while the line is open
and the broker connected, 0 otherwise (also the last will). Deadman: a 0 on arm/{id}/operator, or an
operator that repeated 1 and then fell silent for --operator-lease ms, writes #255PDST! to the line. The port is reopened with back-off
(250 ms doubling to 5 s) and the broker reconnected every second.`,
    )
    .action(async (flags: GatewayFlags) => {
      const env = loadCliConfig();
      const log = createLogger('gateway', env.logLevel);
      const username = flags.username ?? env.mqttUsername;
      const gw = startGateway({
        serialPath: flags.serial,
        baudRate: flags.baud,
        mqttUrl: flags.mqtt ?? env.mqttUrl,
        armId: flags.arm,
        operatorLeaseMs: flags.operatorLease,
        ...(username ? { username, password: flags.password ?? env.mqttPassword } : {}),
        onFirst: firstOnly(log),
        onSerial: (open, reason) =>
          open
            ? log.info({ serial: flags.serial }, 'serial line open')
            : log.warn({ reason }, 'serial line closed; reopening'),
      });
      gw.client.on('connect', () => log.info({ arm: flags.arm }, 'broker connected'));
      gw.client.on('offline', () => log.warn('broker unreachable; reconnecting'));
      await untilSignal(log);
      await gw.stop();
      log.info({ counters: gw.core.counters, serial: gw.link.counters }, 'gateway stopped');
    });
}
