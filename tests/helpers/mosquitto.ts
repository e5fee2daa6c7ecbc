/**
 * A throwaway Mosquitto 2.0 broker: an MQTT listener and a WebSockets listener on free ports
 * of 127.0.0.1, anonymous access, persistence in its temp dir (so `restart()` keeps
 * persistent sessions and queued QoS 1 messages), log in `<dir>/mosquitto.log`.
 * Never uses port 1883, so a system Mosquitto does not matter.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from './files.ts';
import { LOOPBACK } from './ports.ts';
import {
  startService,
  type ServiceLifecycle,
  type ServiceProcess,
  type ServiceSpec,
} from './process.ts';

export interface MosquittoOptions {
  /** Extra mosquitto.conf lines, appended after the generated ones. */
  extraConfig?: string[];
  /** Milliseconds to wait for both listeners to accept connections. */
  startTimeoutMs?: number;
  /** `set_tcp_nodelay true`, as armtwin deploys Mosquitto; false = Mosquitto's own default. */
  tcpNoDelay?: boolean;
}

export const DEFAULT_MOSQUITTO_OPTIONS: Required<MosquittoOptions> = {
  extraConfig: [],
  startTimeoutMs: 15_000,
  tcpNoDelay: true,
};

export interface MosquittoService extends ServiceLifecycle {
  host: string;
  /** MQTT (TCP) port. */
  port: number;
  /** `mqtt://127.0.0.1:<port>` */
  url: string;
  /** WebSockets port. */
  wsPort: number;
  /** `ws://127.0.0.1:<wsPort>` */
  wsUrl: string;
  /** The process id while running (a test may SIGSTOP it: a broker that hangs). */
  readonly pid: number | undefined;
  // The temp dir holds config, persistence file and log; a clean stop() saves persistence, so
  // persistent sessions and their queued messages survive restart().
}

/** Resolves the mosquitto binary: PATH first, then /usr/sbin (not on a normal user's PATH). */
export function mosquittoBinary(): string {
  const dirs = [...(process.env.PATH ?? '').split(path.delimiter), '/usr/sbin', '/usr/local/sbin'];
  for (const dir of dirs) {
    const candidate = path.join(dir, 'mosquitto');
    if (dir && fs.existsSync(candidate)) return candidate;
  }
  throw new Error('mosquitto not found; run scripts/install-deps.sh');
}

function mosquittoConf(
  dir: string,
  port: number,
  wsPort: number,
  extra: string[],
  tcpNoDelay: boolean,
): string {
  return [
    '# written by tests/helpers/mosquitto.ts',
    // Run as root, Mosquitto 2 switches to user "mosquitto", which cannot write our temp dir.
    ...(process.getuid?.() === 0 ? ['user root'] : []),
    'per_listener_settings false',
    'allow_anonymous true',
    `set_tcp_nodelay ${tcpNoDelay}`,
    `listener ${port} ${LOOPBACK}`,
    'protocol mqtt',
    `listener ${wsPort} ${LOOPBACK}`,
    'protocol websockets',
    'persistence true',
    `persistence_location ${dir}/`,
    'log_dest stderr',
    'log_type all',
    'log_timestamp true',
    'log_timestamp_format %Y-%m-%dT%H:%M:%S',
    'connection_messages true',
    ...extra,
    '',
  ].join('\n');
}

/** Starts a throwaway Mosquitto and waits until both listeners accept connections. */
/**
 * The Mosquitto that `armtwin deploy-mosquitto` wrote into `dir` (its `mosquitto.conf`), as a test
 * service on `ports`: logging to stderr, and as root when the tests run as root (Mosquitto 2
 * would switch to user "mosquitto", which cannot read the temp dir).
 */
export function deployedMosquittoSpec(dir: string, ports: number[]): ServiceSpec {
  const conf = path.join(dir, 'mosquitto.conf');
  if (process.getuid?.() === 0) fs.appendFileSync(conf, 'user root\n');
  fs.appendFileSync(conf, 'log_dest stderr\nlog_type all\n');
  return {
    name: 'mosquitto',
    command: mosquittoBinary(),
    args: ['-c', conf],
    dir,
    host: LOOPBACK,
    ports,
    startTimeoutMs: 15_000,
  };
}

/** The certificate files of a deployed Mosquitto's TLS listeners. */
export interface DeployTls {
  certFile: string;
  keyFile: string;
  caFile: string;
}

/**
 * Mosquitto running the configuration `armtwin deploy-mosquitto` generates from `users` (a users
 * file, or one written into the service's dir: passwd, acl, the roles enforced): plain MQTT on loopback on `spec.ports[0]`; with `tls`, MQTTS
 * on `ports[1]` and WSS on `ports[2]` too. The generated files are in `spec.dir`.
 */
export function startDeployedMosquitto(
  name: string,
  users: string | ((dir: string) => string),
  tls?: DeployTls,
): Promise<ServiceProcess> {
  return startService(name, tls ? 3 : 1, (dir, p) => {
    const usersFile = typeof users === 'string' ? users : users(dir);
    const [local, mqtts = 0, wss = 0] = p.map(String);
    const args = ['--persistence-dir', `${dir}/`, '--port', local!, '--bind', '127.0.0.1'];
    args.push('--mqtts-port', String(mqtts), '--wss-port', String(wss));
    if (tls)
      args.push('--certfile', tls.certFile, '--keyfile', tls.keyFile, '--cafile', tls.caFile);
    execFileSync(
      process.execPath,
      [
        path.join(REPO_ROOT, 'apps/cli/bin/armtwin.mjs'),
        'deploy-mosquitto',
        '--users',
        usersFile,
        '--out',
        dir,
        ...args,
      ],
      { cwd: REPO_ROOT, stdio: 'pipe' },
    );
    return deployedMosquittoSpec(dir, p);
  });
}

export async function startMosquitto(opts: MosquittoOptions = {}): Promise<MosquittoService> {
  const o = { ...DEFAULT_MOSQUITTO_OPTIONS, ...opts };
  const command = mosquittoBinary();
  const proc: ServiceProcess = await startService('mosquitto', 2, (dir, ports) => {
    const [port = 0, wsPort = 0] = ports;
    const confFile = path.join(dir, 'mosquitto.conf');
    fs.writeFileSync(confFile, mosquittoConf(dir, port, wsPort, o.extraConfig, o.tcpNoDelay));
    return {
      name: 'mosquitto',
      command,
      args: ['-c', confFile],
      dir,
      host: LOOPBACK,
      ports: [port, wsPort],
      startTimeoutMs: o.startTimeoutMs,
    };
  });
  const [port = 0, wsPort = 0] = proc.spec.ports;
  return {
    host: LOOPBACK,
    port,
    url: `mqtt://${LOOPBACK}:${port}`,
    wsPort,
    wsUrl: `ws://${LOOPBACK}:${wsPort}`,
    dir: proc.spec.dir,
    confFile: path.join(proc.spec.dir, 'mosquitto.conf'),
    logFile: proc.logFile,
    get running() {
      return proc.running;
    },
    get pid() {
      return proc.pid;
    },
    start: () => proc.start(),
    stop: () => proc.stop(),
    restart: async () => {
      await proc.stop();
      await proc.start();
    },
    kill: () => proc.kill(),
    dispose: (d) => proc.dispose(d),
  };
}
