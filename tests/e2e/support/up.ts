/**
 * `armtwin up` (what `npm start` runs) as a child process with a users file, for the security
 * end-to-end tests: the embedded broker with roles, the HUD + /mqtt + /api/whoami on one HTTP
 * port, the simulated arm1; no middleware. Also a watcher that logs in over MQTT and records
 * what the arm says (positions with arrival times, `$ERR` texts, `arm1/operator`).
 */
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { createReader, type Frame } from '@armtwin/protocol';
import { freePorts, REPO_ROOT } from '../../helpers/services.ts';
import { until } from './sim.ts';
import { writeControlUsers } from '../../integration/control-cases.ts';

export const USERS_FILE = path.join(REPO_ROOT, 'deploy', 'users.example.json');
/** The sample users' passwords are `<name>-demo`. */
export const demoPassword = (user: string) => `${user}-demo`;

export interface UpProcess {
  /** `http://127.0.0.1:<port>/`: the HUD; `/mqtt` and `/api` on the same port. */
  url: string;
  httpPort: number;
  mqttUrl: string;
  logFile: string;
  stop(): Promise<void>;
}

/**
 * `npm start`'s `armtwin up` (no HUD build, no middleware) on free ports. Without the second arm
 * unless `so101` (its emulated bus polls all the time: load a spec about arm1 does not need).
 */
export async function startUp(
  logFile: string,
  extraArgs: string[] = [],
  usersFile = USERS_FILE,
  { so101 = false }: { so101?: boolean } = {},
): Promise<UpProcess> {
  const [httpPort = 0, mqttPort = 0] = await freePorts(2);
  fs.mkdirSync(path.dirname(logFile), { recursive: true });
  const child = spawn(
    process.execPath,
    [
      'scripts/start.mjs',
      '--no-web',
      '--no-middleware',
      ...(so101 ? [] : ['--no-so101']),
      '--port',
      String(httpPort),
      '--mqtt-port',
      String(mqttPort),
      ...extraArgs,
    ],
    {
      cwd: REPO_ROOT,
      env: { ...process.env, ARMTWIN_USERS: usersFile, ARMTWIN_TLS_CERT: '', ARMTWIN_TLS_KEY: '' },
      stdio: ['ignore', 'pipe', 'pipe'],
    },
  );
  let out = '';
  const log = fs.createWriteStream(logFile);
  const take = (d: Buffer) => {
    out += d.toString();
    log.write(d);
  };
  child.stdout.on('data', take);
  child.stderr.on('data', take);
  const exited = new Promise<void>((resolve) => child.once('exit', () => resolve()));
  const stop = async () => {
    if (child.exitCode === null && child.signalCode === null) child.kill('SIGINT');
    const timer = setTimeout(() => child.kill('SIGKILL'), 10_000);
    await exited;
    clearTimeout(timer);
    log.end();
  };
  try {
    await until(
      () => {
        if (child.exitCode !== null) throw new Error(`armtwin up exited:\n${out}`);
        return out.includes('armtwin is running');
      },
      60_000,
      'armtwin up to start',
    );
  } catch (err) {
    await stop();
    throw err;
  }
  return {
    url: `http://127.0.0.1:${httpPort}/`,
    httpPort,
    mqttUrl: `mqtt://127.0.0.1:${mqttPort}`,
    logFile,
    stop,
  };
}

/** Logs in as `user` and records arm `armId`'s status and operator topics. */
/**
 * `armtwin up` with the control tests' users (alice, bob, carol, the arm1 device; passwords
 * `demoPassword`), its log in `outputDir`; `stop` also removes the users file's folder.
 */
export async function startUpWithControlUsers(name: string, outputDir: string): Promise<UpProcess> {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), `armtwin-e2e-${name}-`));
  const up = await startUp(
    path.join(outputDir, `armtwin-up-${name}-${process.pid}.log`),
    [],
    writeControlUsers(dir, demoPassword),
  );
  return {
    ...up,
    async stop() {
      await up.stop();
      fs.rmSync(dir, { recursive: true, force: true });
    },
  };
}

export class ArmWatcher {
  /** Base servo pulses with their arrival time (ms epoch). */
  readonly positions: { at: number; id: number; pwm: number }[] = [];
  readonly errors: { at: number; text: string }[] = [];
  readonly operator: { at: number; text: string; retain: boolean }[] = [];
  private readonly reader = createReader({
    onFrame: (f) => this.take(f),
    onGroup: (g) => g.frames.forEach((f) => this.take(f)),
  });

  private constructor(readonly client: MqttClient) {}

  static async connect(url: string, armId: string, user: string): Promise<ArmWatcher> {
    const client = await mqtt.connectAsync(url, {
      username: user,
      password: demoPassword(user),
      clientId: `e2e-watch-${user}-${process.pid}-${Date.now()}`,
      reconnectPeriod: 500,
    });
    const w = new ArmWatcher(client);
    client.on('message', (topic, payload, packet) => {
      if (topic === `arm/${armId}/status`) w.reader.feed(payload.toString('latin1'));
      else if (topic === `arm/${armId}/operator`)
        w.operator.push({ at: Date.now(), text: payload.toString(), retain: packet.retain });
    });
    await client.subscribeAsync([`arm/${armId}/status`, `arm/${armId}/operator`], { qos: 1 });
    return w;
  }

  private take(f: Frame): void {
    if (f.type === 'position') this.positions.push({ at: Date.now(), id: f.id, pwm: f.pwm });
    else if (f.type === 'controllerError') this.errors.push({ at: Date.now(), text: f.text });
  }

  /** The latest reported pulse of servo `id` (NaN = none yet). */
  pwm(id: number): number {
    for (let i = this.positions.length - 1; i >= 0; i--)
      if (this.positions[i]!.id === id) return this.positions[i]!.pwm;
    return NaN;
  }

  /** Pulses of servo `id` that arrived in [from, to). */
  pwmBetween(id: number, from: number, to: number): number[] {
    return this.positions.filter((p) => p.id === id && p.at >= from && p.at < to).map((p) => p.pwm);
  }

  async close(): Promise<void> {
    await this.client.endAsync(true);
  }
}

/** A bundled profile as JSON, loosely typed for a test to change. */
export type ProfileJson = Record<string, unknown> & {
  name: string;
  servos: Record<string, unknown>[];
};

/**
 * `armtwin up` with arm1 as `name`: a copy of the bundled armtwin5 (URDF, meshes, profile) in a
 * models folder of its own, its profile changed by `edit`; `file` is the copy's profile.json,
 * and `stop` also removes the folder.
 */
export async function startUpWithProfile(
  name: string,
  outputDir: string,
  edit: (profile: ProfileJson) => ProfileJson = (p) => p,
): Promise<UpProcess & { file: string }> {
  const models = fs.mkdtempSync(path.join(os.tmpdir(), `armtwin-e2e-${name}-`));
  const dir = path.join(models, name);
  const file = path.join(dir, 'profile.json');
  fs.cpSync(path.join(REPO_ROOT, 'public/models/armtwin5'), dir, { recursive: true });
  const profile = JSON.parse(fs.readFileSync(file, 'utf8')) as ProfileJson;
  fs.writeFileSync(file, JSON.stringify(edit({ ...profile, name })));
  const removeModels = () => fs.rmSync(models, { recursive: true, force: true });
  let up: UpProcess;
  try {
    up = await startUp(path.join(outputDir, `armtwin-up-${name}-${process.pid}.log`), [
      '--models',
      models,
      '--arms',
      `arm1:${name}`,
    ]);
  } catch (err) {
    removeModels();
    throw err;
  }
  return {
    ...up,
    file,
    async stop() {
      await up.stop();
      removeModels();
    },
  };
}
