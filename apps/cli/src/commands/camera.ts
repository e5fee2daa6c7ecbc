/**
 * `armtwin camera`: serves one camera through ffmpeg (MJPEG over HTTP, H.264 over a WebSocket)
 * and announces it on MQTT (PROTOCOL.md §7). Parses options and calls `@armtwin/camera`.
 */
import fs from 'node:fs';
import { InvalidArgumentError, Option, type Command } from 'commander';
import { LoginThrottle, loadUsers } from '@armtwin/auth';
import {
  CAMERA_KINDS,
  DEFAULT_ENCODER_OPTIONS,
  DEFAULT_SERVE_CAMERA_OPTIONS,
  ffmpegVersion,
  isValidCamId,
  parseSource,
  serveCamera,
  type CameraKind,
  type CameraPose,
} from '@armtwin/camera';
import { loadCliConfig } from '../config.ts';
import { createLogger, firstOnly } from '../log.ts';
import { armId, number } from './options.ts';
import { untilSignal } from './signals.ts';

interface CameraFlags {
  arm: string;
  name: string;
  source: string;
  label?: string;
  pose?: CameraPose;
  fov?: number;
  kinds: CameraKind[];
  reserve?: boolean;
  size: [number, number];
  fps: number;
  host?: string;
  port: number;
  publicUrl?: string;
  mqtt?: string;
  announce: boolean;
  username?: string;
  password?: string;
  users?: string;
  token?: string;
}

const camId = (value: string): string => {
  if (!isValidCamId(value))
    throw new InvalidArgumentError('camera name must match [a-z0-9-]{1,32}');
  return value;
};

/** Checked here, passed on as written. */
const source = (value: string): string => {
  try {
    parseSource(value);
    return value;
  } catch (err) {
    throw new InvalidArgumentError((err as Error).message);
  }
};

const triple = (text: string): [number, number, number] | null => {
  const v = text.split(',').map(Number);
  return v.length === 3 && v.every(Number.isFinite) ? (v as [number, number, number]) : null;
};

/** `x,y,z:x,y,z` in mm: the camera's position, then the point it looks at. */
const pose = (value: string): CameraPose => {
  const [p, l] = value.split(':').map(triple);
  if (!p || !l) throw new InvalidArgumentError('pose is x,y,z:x,y,z (mm: position, then look-at)');
  return { position: p, lookAt: l };
};

const kinds = (value: string): CameraKind[] => {
  const list = value.split(',').map((k) => k.trim());
  const bad = list.filter((k) => !CAMERA_KINDS.includes(k as CameraKind));
  if (bad.length || list.length === 0)
    throw new InvalidArgumentError(`kinds are ${CAMERA_KINDS.join(', ')}`);
  return list as CameraKind[];
};

const size = (value: string): [number, number] => {
  const m = /^(\d{2,4})x(\d{2,4})$/.exec(value);
  if (!m) throw new InvalidArgumentError('size is WIDTHxHEIGHT, e.g. 640x480');
  return [Number(m[1]), Number(m[2])];
};

export function registerCamera(program: Command): void {
  program
    .command('camera')
    .description('serve one camera of an arm (MJPEG and H.264 via ffmpeg) and announce it on MQTT')
    .requiredOption('--name <camId>', 'camera id, [a-z0-9-]{1,32}', camId)
    .requiredOption(
      '--source <source>',
      'testsrc, a V4L2 device (/dev/video0), an rtsp:// URL or an http(s):// MJPEG URL',
      source,
    )
    .option('--arm <id>', 'arm id', armId, 'arm1')
    .option('--label <text>', 'name shown in the HUD (default: --name)')
    .option('--pose <x,y,z:x,y,z>', "position and look-at point, mm, in the arm's frame", pose)
    .option('--fov <deg>', 'vertical field of view, degrees', number('fov', 1, 179))
    .addOption(
      new Option('--kinds <list>', 'streams served, the first announced as the main one')
        .argParser(kinds)
        .default(['mjpeg', 'h264-ws'], 'mjpeg,h264-ws'),
    )
    .option(
      '--reserve',
      'an http(s) MJPEG source: re-serve it through ffmpeg instead of announcing its URL',
    )
    .addOption(
      new Option('--size <WxH>', 'frame size')
        .argParser(size)
        .default(
          [DEFAULT_ENCODER_OPTIONS.width, DEFAULT_ENCODER_OPTIONS.height],
          `${DEFAULT_ENCODER_OPTIONS.width}x${DEFAULT_ENCODER_OPTIONS.height}`,
        ),
    )
    .option(
      '--fps <n>',
      'frame rate (test source, V4L2)',
      number('fps', 1, 120),
      DEFAULT_ENCODER_OPTIONS.fps,
    )
    .option(
      '--host <addr>',
      'listen address (env ARMTWIN_HOST; beyond loopback needs --users or --token)',
    )
    .option(
      '--port <n>',
      'HTTP port (0 = any free one)',
      number('port', 0, 65535, true),
      DEFAULT_SERVE_CAMERA_OPTIONS.port,
    )
    .option(
      '--public-url <url>',
      'base URL viewers reach this server at (default http(s)://host:port)',
    )
    .option('--mqtt <url>', 'broker URL (env MQTT_URL)')
    .addOption(new Option('--no-announce', 'serve only, announce nothing'))
    .option('--username <name>', 'broker user name, a device user of the arm (env MQTT_USERNAME)')
    .option('--password <secret>', 'broker password (env MQTT_PASSWORD)')
    .option('--users <file>', 'users file: viewers need a log-in (env ARMTWIN_USERS)')
    .option('--token <token>', 'a bearer token that may watch (env API_TOKEN)')
    .addHelpText(
      'after',
      `
Streams: GET /camera/<name>.mjpeg (multipart/x-mixed-replace, X-Timestamp per part), WebSocket
/camera/<name>.h264 (H.264 access units behind a 16-byte header: packages/camera/README.md),
GET /camera/<name>.jpg (the latest picture), GET /camera/metrics (counters). The camera is
announced retained on arm/<arm>/camera/<name>; the last will and a clean stop remove it. ffmpeg is
restarted with back-off (0.5 s doubling to 10 s) when it stops or its source stalls for 10 s.
With --users or --token, viewers log in: HTTP Basic or Bearer, or ?auth=<base64 name:password> /
?access_token=<token> where a browser cannot send headers. TLS: ARMTWIN_TLS_CERT and _KEY.`,
    )
    .action(async (flags: CameraFlags) => {
      const env = loadCliConfig();
      const log = createLogger('camera', env.logLevel);
      const viaUrl = parseSource(flags.source).type === 'mjpeg-url';
      const reserve = viaUrl && flags.reserve === true;
      if ((!viaUrl || reserve) && !ffmpegVersion())
        throw new Error(
          'ffmpeg not found: install it (scripts/install-deps.sh, or apt install ffmpeg)',
        );
      const usersFile = flags.users ?? env.usersFile;
      const username = flags.username ?? env.mqttUsername;
      const [width, height] = flags.size;
      const served = await serveCamera({
        cameras: [
          {
            armId: flags.arm,
            camId: flags.name,
            label: flags.label ?? flags.name,
            source: flags.source,
            kinds: flags.kinds,
            passThrough: !reserve,
            ...(flags.pose ? { pose: flags.pose } : {}),
            ...(flags.fov !== undefined ? { fovDeg: flags.fov } : {}),
          },
        ],
        encoder: { width, height, fps: flags.fps },
        host: flags.host ?? env.host,
        port: flags.port,
        publicUrl: flags.publicUrl ?? '',
        tls: env.tlsCert
          ? { cert: fs.readFileSync(env.tlsCert), key: fs.readFileSync(env.tlsKey) }
          : null,
        mqttUrl: flags.announce ? (flags.mqtt ?? env.mqttUrl) : '',
        ...(username ? { username, password: flags.password ?? env.mqttPassword } : {}),
        access: {
          logins: usersFile ? new LoginThrottle(loadUsers(usersFile)) : null,
          token: flags.token ?? env.apiToken,
        },
        onFirst: firstOnly(log),
        log,
      });
      process.stdout.write(`${served.url}/camera/${flags.name}.mjpeg\n`);
      await untilSignal(log);
      await served.stop();
    });
}
