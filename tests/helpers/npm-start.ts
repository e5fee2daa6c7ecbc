/**
 * `npm start` as a terminal runs it, for the tests of what a newcomer's first command does: real
 * npm in a process group of its own (a shell's foreground job, so a test can send the group a
 * Ctrl-C's SIGINT), on free HTTP and MQTT ports, the middleware's local influxd on free ports
 * with its data and spool in `dir`. `kill()` SIGKILLs the group, whatever state it is in.
 */
import { spawn } from 'node:child_process';
import path from 'node:path';
import { canConnect, freePorts, LOOPBACK } from './ports.ts';
import { REPO_ROOT } from './files.ts';

export interface NpmStart {
  /** The process group (npm's pid). */
  group: number;
  mqttPort: number;
  /** The local influxd's HTTP URL. */
  influxUrl: string;
  influxPort: number;
  /** Everything printed so far, stdout and stderr. */
  output(): string;
  /** Resolves with the signal npm ended by, or `code N`. */
  exited: Promise<string>;
  /** Whether npm has ended. */
  hasExited(): boolean;
  /** SIGINT to the whole group, as Ctrl-C in a terminal. */
  interrupt(): void;
  kill(): void;
}

/** Two free ports for a local influxd: HTTP on `p`, RPC on `p + 2`. */
export async function freeInfluxPort(): Promise<number> {
  for (;;) {
    const [p = 0] = await freePorts(1);
    if (p + 2 <= 65535 && !(await canConnect(LOOPBACK, p + 2))) return p;
  }
}

/** SIGKILL, ignoring a process already gone. */
export function tryKill(pid: number): void {
  try {
    process.kill(pid, 'SIGKILL');
  } catch {
    // already gone
  }
}

/** Starts `npm start -- … args`; the spool is `dir/spool`, influxd's data `dir/influx`. */
export async function startNpm(dir: string, args: string[] = []): Promise<NpmStart> {
  const [httpPort = 0, mqttPort = 0] = await freePorts(2);
  const influxPort = await freeInfluxPort();
  const npm = spawn(
    'npm',
    ['start', '--', '--port', String(httpPort), '--mqtt-port', String(mqttPort), ...args],
    {
      cwd: REPO_ROOT,
      env: {
        ...process.env,
        SPOOL_DIR: path.join(dir, 'spool'),
        ARMTWIN_INFLUX_DATA: path.join(dir, 'influx'),
        ARMTWIN_INFLUX_PORT: String(influxPort),
        INFLUX_URL: '',
      },
      stdio: ['ignore', 'pipe', 'pipe'],
      // A process group of its own, as a shell gives a foreground job.
      detached: true,
    },
  );
  const group = npm.pid ?? 0;
  let out = '';
  npm.stdout.on('data', (d: Buffer) => (out += d.toString()));
  npm.stderr.on('data', (d: Buffer) => (out += d.toString()));
  let ended = false;
  const exited = new Promise<string>((resolve) =>
    npm.once('exit', (code, signal) => {
      ended = true;
      resolve(signal ?? `code ${code}`);
    }),
  );
  return {
    group,
    mqttPort,
    influxPort,
    influxUrl: `http://${LOOPBACK}:${influxPort}`,
    output: () => out,
    exited,
    hasExited: () => ended,
    interrupt: () => process.kill(-group, 'SIGINT'),
    kill: () => {
      if (group) for (const pid of [-group, group]) tryKill(pid);
    },
  };
}
