import fs from 'node:fs';
import path from 'node:path';
import { InvalidArgumentError, type Command } from 'commander';
import { DEFAULT_PROFILE, PROFILE_NAME } from '@armtwin/sim';
import { DEFAULT_MODEL_COPIES_OPTIONS, parseExtraSources, runUp, SO101_ARM } from '@armtwin/up';
import { startArmInRos, type ArmInRos } from '@armtwin/ros2';
import { DEFAULT_FOXGLOVE_PORT } from '@armtwin/foxglove';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { armId, number } from './options.ts';
import { untilSignal } from './signals.ts';

/** `arm1:armtwin5,arm2:track6` → arms and profiles (a bare id gets the default, armtwin5). */
export function parseArms(value: string): { id: string; profile: string }[] {
  const arms = value.split(',').map((part) => {
    const [id = '', profile = DEFAULT_PROFILE, extra] = part.trim().split(':');
    if (extra !== undefined || !PROFILE_NAME.test(profile))
      throw new InvalidArgumentError(`"${part}": expected id[:profile], profile [a-z0-9_-]{1,32}`);
    return { id: armId(id), profile };
  });
  if (new Set(arms.map((a) => a.id)).size !== arms.length)
    throw new InvalidArgumentError('each arm id may appear once');
  return arms;
}

/** `--csp-sources` / ARMTWIN_CSP_SOURCES: a bad source is a usage error naming it. */
function cspSources(value: string): string[] {
  try {
    return parseExtraSources(value);
  } catch (err) {
    throw new InvalidArgumentError((err as Error).message);
  }
}

interface UpFlags {
  users?: string;
  port?: number;
  mqttPort?: number;
  host?: string;
  arm: string;
  arms?: { id: string; profile: string }[];
  rate: number;
  web: boolean;
  middleware: boolean;
  camera?: string;
  models?: string;
  cspSources?: string[];
  modelIdle?: number;
  ros2?: boolean;
  so101: boolean;
  foxglove?: number | true;
}

export function registerUp(program: Command): void {
  program
    .command('up')
    .description(
      'run the whole twin: broker, HUD + /mqtt + /api on one HTTP port, the simulated arm, an SO-101 on an emulated servo bus, the middleware',
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
      'listen address (env ARMTWIN_HOST, default 127.0.0.1; beyond loopback needs --users)',
    )
    .option('--users <file>', 'users-and-roles file (env ARMTWIN_USERS): log-ins and roles')
    .option('--arm <id>', 'id of the simulated arm', armId, 'arm1')
    .option(
      '--arms <list>',
      'several simulated arms with their profiles, e.g. arm1:armtwin5,arm2:track6 (replaces --arm)',
      parseArms,
    )
    .option('--rate <hz>', 'state rate of the simulated arm, Hz', number('rate', 1, 1000), 50)
    .option(
      '--models <dir>',
      'an extra folder of robot profiles, served at /models/ (before public/models) and read by --arms',
    )
    .option(
      '--model-idle <minutes>',
      `a model copy (/api/arms/{id}/model) with nothing sent to it stops after this long (default ${DEFAULT_MODEL_COPIES_OPTIONS.idleMs / 60_000})`,
      number('model idle time', 0.1, 1440),
    )
    .option(
      '--ros2',
      'show every simulated arm in ROS 2 as `armtwin ros2 --arm ID` does (ROS_DOMAIN_ID; anonymous demo only; docs/ros2.md)',
    )
    .option(
      '--no-so101',
      `do not start the second arm, "${SO101_ARM.id}": a simulated SO-101 on an emulated Feetech bus behind the bus gateway (needs socat)`,
    )
    .option(
      '--foxglove [port]',
      `a live Foxglove WebSocket server for Foxglove and Lichtblick (default port ${DEFAULT_FOXGLOVE_PORT}; docs/foxglove.md)`,
      number('port', 0, 65535, true),
    )
    .option('--no-web', 'do not build the HUD when apps/web/dist is missing')
    .option('--no-middleware', 'do not start the middleware')
    .option(
      '--camera <source>',
      'a demo camera of the first arm through ffmpeg: testsrc, /dev/video0, rtsp://… or an MJPEG URL',
    )
    .option(
      '--csp-sources <list>',
      "other brokers and camera servers the HUD may reach, e.g. 'wss://broker.lab https://cams.lab:8443' (env ARMTWIN_CSP_SOURCES; added to its Content-Security-Policy)",
      cspSources,
    )
    .addHelpText(
      'after',
      `
Security (SECURITY.md): without a users file this is the ANONYMOUS local demo, on loopback only.
With --users/ARMTWIN_USERS every MQTT client logs in and its role is enforced, and /api (but
/api/healthz) needs API_TOKEN as a bearer token or a user's password (HTTP Basic).
ARMTWIN_TLS_CERT + ARMTWIN_TLS_KEY: HTTPS, WSS (/mqtt) and MQTTS with that certificate.
Storage: INFLUX_URL if set; otherwise a local influxd with its data in .armtwin/influx (if it
can be started); otherwise none, said plainly. If the default MQTT port 1883 is taken (another
broker), the embedded broker takes a free port and prints it; an explicitly given port that is
taken is an error. The HUD connects to ws(s)://<host>/mqtt on the HTTP port either way.
Ctrl-C stops everything: the arm says offline, the middleware flushes, influxd stops.`,
    )
    .action(async (flags: UpFlags) => {
      const env = loadCliConfig();
      if (flags.ros2 && (flags.users ?? env.usersFile))
        program.error(
          '--ros2 is for the anonymous demo: with users, run `armtwin ros2 --username …`',
        );
      const log = createLogger('up', env.logLevel);
      const say = (msg: string) => process.stderr.write(`armtwin: ${msg}\n`);
      const up = await runUp({
        usersFile: flags.users ?? env.usersFile,
        tlsCert: env.tlsCert,
        tlsKey: env.tlsKey,
        apiToken: env.apiToken,
        httpPort: flags.port ?? env.httpPort,
        mqttPort: flags.mqttPort ?? env.mqttPort,
        mqttPortFallback: flags.mqttPort === undefined && !process.env.ARMTWIN_MQTT_PORT,
        host: flags.host ?? env.host,
        armId: flags.arm,
        ...(flags.arms ? { arms: flags.arms } : {}),
        ...(flags.so101 ? { so101: SO101_ARM.id } : {}),
        rate: flags.rate,
        influxUrl: env.influxUrl,
        buildWeb: flags.web,
        middleware: flags.middleware,
        ...(flags.camera ? { camera: flags.camera } : {}),
        ...(flags.foxglove === undefined
          ? {}
          : { foxglovePort: flags.foxglove === true ? DEFAULT_FOXGLOVE_PORT : flags.foxglove }),
        ...(flags.models ? { modelsDir: path.resolve(flags.models) } : {}),
        cspSources: flags.cspSources ?? cspSources(env.cspSources),
        ...(flags.modelIdle ? { modelIdleMs: flags.modelIdle * 60_000 } : {}),
        env: process.env,
        say,
        onFirst: firstOnly(log),
      });
      let inRos: ArmInRos[] = [];
      try {
        if (flags.ros2) inRos = await showInRos2(up.broker.url, flags, firstOnly(log), say);
      } catch (err) {
        say(`ros2: ${(err as Error).message}`);
        await up.stop();
        process.exitCode = 1;
        return;
      }
      process.stdout.write(`\n  armtwin is running: open ${up.url}\n  (Ctrl-C to stop)\n\n`);
      await untilSignal();
      say('stopping…');
      for (const arm of inRos) await arm.stop();
      await up.stop();
      say('stopped');
      process.exitCode = 0;
    });
}

/** `--ros2`: each simulated arm as `armtwin ros2 --arm ID --profile P` would show it. */
function showInRos2(
  mqttUrl: string,
  flags: UpFlags,
  onFirst: (kind: string, message: string) => void,
  say: (msg: string) => void,
): Promise<ArmInRos[]> {
  const arms = flags.arms ?? [{ id: flags.arm, profile: DEFAULT_PROFILE }];
  const extra = flags.models ? path.resolve(flags.models) : undefined;
  return Promise.all(
    arms.map((a) =>
      startArmInRos({
        mqttUrl,
        armId: a.id,
        profile: a.profile,
        modelsDir:
          extra && fs.existsSync(path.join(extra, a.profile, 'profile.json')) ? extra : undefined,
        onFirst,
        onInfo: (message) => say(`ros2: ${message}`),
      }),
    ),
  );
}
