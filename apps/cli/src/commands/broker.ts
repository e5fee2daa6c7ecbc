import type { Command } from 'commander';
import { loadBrokerSecurity, serveBroker } from '@armtwin/broker';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { number } from './options.ts';
import { untilSignal } from './signals.ts';

export function registerBroker(program: Command): void {
  program
    .command('broker')
    .description('run the embedded MQTT broker (Aedes, in memory) on its own')
    .option(
      '--port <port>',
      'MQTT/TCP port (env ARMTWIN_MQTT_PORT, default 1883)',
      number('port', 0, 65535, true),
    )
    .option(
      '--ws-port <port>',
      'also serve MQTT over WebSockets at ws(s)://host:PORT/mqtt',
      number('port', 0, 65535, true),
    )
    .option('--host <addr>', 'listen address (env ARMTWIN_HOST, default 127.0.0.1)')
    .option(
      '--users <file>',
      'users-and-roles file (env ARMTWIN_USERS); without it: anonymous, loopback only',
    )
    .addHelpText(
      'after',
      `
TLS: ARMTWIN_TLS_CERT and ARMTWIN_TLS_KEY (PEM) make the MQTT port mqtts:// and the WebSockets
port wss://. Roles and the users file: SECURITY.md.`,
    )
    .action(async (flags: { port?: number; wsPort?: number; host?: string; users?: string }) => {
      const env = loadCliConfig();
      const log = createLogger('broker', env.logLevel);
      const host = flags.host ?? env.host;
      const security = loadBrokerSecurity({ ...env, usersFile: flags.users ?? env.usersFile });
      const denied = firstOnly(log);
      const served = await serveBroker({
        host,
        port: flags.port ?? env.mqttPort,
        wsPort: flags.wsPort,
        ...security,
        log,
        onDenied: (what, detail) =>
          denied(`denied:${what}`, `${what} refused ${JSON.stringify(detail)}`),
      });
      await untilSignal(log);
      await served.stop();
    });
}
