import http from 'node:http';
import type { Command } from 'commander';
import { startBroker } from '../broker/broker.ts';
import { loadCliConfig } from '../config.ts';
import { createLogger } from '../log.ts';
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
      'also serve MQTT over WebSockets at ws://host:PORT/mqtt',
      number('port', 0, 65535, true),
    )
    .option('--host <addr>', 'listen address (env ARMTWIN_HOST, default 127.0.0.1)')
    .action(async (flags: { port?: number; wsPort?: number; host?: string }) => {
      const env = loadCliConfig();
      const log = createLogger('broker', env.logLevel);
      const host = flags.host ?? env.host;
      const broker = await startBroker({ host, port: flags.port ?? env.mqttPort });
      let server: http.Server | undefined;
      if (flags.wsPort !== undefined) {
        server = http.createServer((_req, res) => res.writeHead(404).end());
        broker.attach(server);
        await new Promise<void>((resolve, reject) =>
          server!.once('error', reject).listen(flags.wsPort, host, resolve),
        );
        const a = server.address();
        log.info(
          { url: `ws://${host}:${typeof a === 'object' && a ? a.port : flags.wsPort}/mqtt` },
          'MQTT over WebSockets',
        );
      }
      broker.aedes.on('client', (c) => log.debug({ id: c.id }, 'client connected'));
      log.info({ url: broker.url }, 'MQTT broker listening');
      await untilSignal(log);
      server?.closeAllConnections();
      await broker.close();
      server?.close();
    });
}
