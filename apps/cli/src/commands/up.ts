import type { Command } from 'commander';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { startUp } from '../start/up.ts';
import { untilSignal } from './signals.ts';
import { armId, number } from './sim.ts';

interface UpFlags {
  port?: number;
  mqttPort?: number;
  host?: string;
  arm: string;
  rate: number;
  web: boolean;
  middleware: boolean;
}

export function registerUp(program: Command): void {
  program
    .command('up')
    .description(
      'run the whole twin: broker, HUD + /mqtt + /api on one HTTP port, the simulated arm, the middleware',
    )
    .option(
      '--port <port>',
      'HTTP port (env ARMTWIN_PORT, default 8080)',
      number('port', 0, 65535, true),
    )
    .option(
      '--mqtt-port <port>',
      'MQTT/TCP port of the embedded broker (env ARMTWIN_MQTT_PORT, default 1883)',
      number('port', 0, 65535, true),
    )
    .option(
      '--host <addr>',
      'listen address (env ARMTWIN_HOST, default 127.0.0.1; 0.0.0.0 for the LAN)',
    )
    .option('--arm <id>', 'id of the simulated arm', armId, 'arm1')
    .option('--rate <hz>', 'state rate of the simulated arm, Hz', number('rate', 1, 1000), 50)
    .option('--no-web', 'do not build the HUD when apps/web/dist is missing')
    .option('--no-middleware', 'do not start the middleware')
    .addHelpText(
      'after',
      `
Storage: INFLUX_URL if set; otherwise a local influxd with its data in .armtwin/influx (if it
can be started); otherwise none, said plainly. If the default MQTT port 1883 is taken (another
broker), the embedded broker takes a free port and prints it; an explicitly given port that is
taken is an error. The HUD connects to ws(s)://<host>/mqtt on the HTTP port either way.
Ctrl-C stops everything: the arm says offline, the middleware flushes, influxd stops.`,
    )
    .action(async (flags: UpFlags) => {
      const env = loadCliConfig();
      const log = createLogger('up', env.logLevel);
      const say = (msg: string) => process.stderr.write(`armtwin: ${msg}\n`);
      const up = await startUp({
        httpPort: flags.port ?? env.httpPort,
        mqttPort: flags.mqttPort ?? env.mqttPort,
        mqttPortFallback: flags.mqttPort === undefined && !process.env.ARMTWIN_MQTT_PORT,
        host: flags.host ?? env.host,
        armId: flags.arm,
        rate: flags.rate,
        influxUrl: env.influxUrl,
        buildWeb: flags.web,
        middleware: flags.middleware,
        env: process.env,
        say,
        onFirst: firstOnly(log),
      });
      say(
        `broker: MQTT on ${up.broker.url}, MQTT over WebSockets on ${up.url.replace(/^http/, 'ws')}mqtt`,
      );
      say(`simulated arm "${flags.arm}" streaming at ${flags.rate} Hz`);
      process.stdout.write(`\n  armtwin is running: open ${up.url}\n  (Ctrl-C to stop)\n\n`);
      await untilSignal();
      say('stopping…');
      await up.stop();
      say('stopped');
      process.exitCode = 0;
    });
}
