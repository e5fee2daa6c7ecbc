import http from 'node:http';
import https from 'node:https';
import type { Command } from 'commander';
import { startBroker } from '../broker/broker.ts';
import { describeSecurity, loadBrokerSecurity } from '../broker/security.ts';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { untilSignal } from './signals.ts';
import { number } from './sim.ts';

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
      const broker = await startBroker({
        host,
        port: flags.port ?? env.mqttPort,
        ...security,
        onDenied: (what, detail) =>
          denied(`denied:${what}`, `${what} refused ${JSON.stringify(detail)}`),
      });
      let server: http.Server | https.Server | undefined;
      if (flags.wsPort !== undefined) {
        const notFound = (_req: http.IncomingMessage, res: http.ServerResponse) =>
          res.writeHead(404).end();
        server = security.tls
          ? https.createServer({ ...security.tls, minVersion: 'TLSv1.2' }, notFound)
          : http.createServer(notFound);
        broker.attach(server);
        await new Promise<void>((resolve, reject) =>
          server!.once('error', reject).listen(flags.wsPort, host, resolve),
        );
        const a = server.address();
        log.info(
          {
            url: `${security.tls ? 'wss' : 'ws'}://${host}:${typeof a === 'object' && a ? a.port : flags.wsPort}/mqtt`,
          },
          'MQTT over WebSockets',
        );
      }
      broker.aedes.on('client', (c) => log.debug({ id: c.id }, 'client connected'));
      log.info(
        { url: broker.url, security: describeSecurity(security, host) },
        'MQTT broker listening',
      );
      await untilSignal(log);
      server?.closeAllConnections();
      await broker.close();
      server?.close();
      log.info({ counters: broker.counters }, 'broker stopped');
    });
}
