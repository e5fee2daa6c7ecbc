/**
 * The second arm of `armtwin up`: a simulated SO-101 on an emulated Feetech bus, driven by the
 * real bus gateway, so a newcomer sees both worlds (a frame controller, arm1; a servo bus) at
 * first look. The pieces are the ones `armtwin sim --bus feetech --serial A` and `armtwin gateway
 * --bus feetech --serial B` run, joined by a socat pseudo-terminal pair A ⇄ B: the emulated
 * servos (`@armtwin/sim`'s bus sim on `@armtwin/servo-bus`) on one end, the gateway
 * (`@armtwin/gateway`: sync reads, the controller core's limits, zones, lease and e-stop) on the
 * other, its MQTT client an in-process device of the embedded broker. `stop()` takes the gateway
 * down first (the arm says offline), then the emulated bus, then socat; socat is also killed when
 * this process exits any other way.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Broker } from '@armtwin/broker';
import { DEFAULT_BUS_GATEWAY_OPTIONS, startBusGateway, type BusGateway } from '@armtwin/gateway';
import { loadSimProfile, startBusSim, type BusSim } from '@armtwin/sim';

/** The id and profile of `npm start`'s second arm (`--no-so101` leaves it out). */
export const SO101_ARM = { id: 'so101', profile: 'so101' } as const;

export interface So101PartOptions {
  broker: Broker;
  armId: string;
  /** The profile's name and the folder that holds it. */
  profile: string;
  modelsDir: string;
  onFirst: (kind: string, message: string) => void;
  /** How long socat may take to make the pair, ms. */
  ptyTimeoutMs?: number;
}

export interface So101Part {
  /** The folder of the pair's two ends: `bus` (the emulated servos) and `gateway`. */
  ptyDir: string;
  gateway: BusGateway;
  stop(): Promise<void>;
}

/** Starts socat, the emulated bus and the gateway; throws (having undone what started) if one fails. */
export async function startSo101Part(o: So101PartOptions): Promise<So101Part> {
  const { profile } = loadSimProfile(o.profile, o.modelsDir);
  const ptyDir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-so101-'));
  const busSide = path.join(ptyDir, 'bus');
  const gatewaySide = path.join(ptyDir, 'gateway');
  const baudRate = DEFAULT_BUS_GATEWAY_OPTIONS.baudRate;
  const socat = await startPtyPair(busSide, gatewaySide, o.ptyTimeoutMs ?? 5000).catch(
    (err: unknown) => {
      fs.rmSync(ptyDir, { recursive: true, force: true });
      throw err;
    },
  );
  const bus: BusSim = await startBusSim({
    protocol: 'feetech',
    profile,
    path: busSide,
    baudRate,
    onFirst: o.onFirst,
  }).catch(async (err: unknown) => {
    await socat.stop();
    fs.rmSync(ptyDir, { recursive: true, force: true });
    throw err;
  });
  const gateway = startBusGateway({
    serialPath: gatewaySide,
    mqttUrl: o.broker.url,
    armId: o.armId,
    bus: 'feetech',
    profile: o.profile,
    modelsDir: o.modelsDir,
    baudRate,
    onFirst: o.onFirst,
    connect: (options) =>
      o.broker.connectInProcess(
        { name: `gateway-${o.armId}`, role: 'device', arm: o.armId },
        options,
      ),
  });
  let stopping: Promise<void> | undefined;
  return {
    ptyDir,
    gateway,
    stop: () =>
      (stopping ??= (async () => {
        await gateway.stop();
        await bus.stop();
        await socat.stop();
        fs.rmSync(ptyDir, { recursive: true, force: true });
      })()),
  };
}

interface PtyPair {
  stop(): Promise<void>;
}

/**
 * util-linux's setpriv, where there is one: socat is started through it with `--pdeathsig KILL`,
 * so the kernel ends socat even when this process is SIGKILLed (no 'exit' handler runs then).
 */
const SETPRIV = '/usr/bin/setpriv';

/** socat's two linked pseudo-terminals at `a` and `b`, raw, without echo. */
async function startPtyPair(a: string, b: string, timeoutMs: number): Promise<PtyPair> {
  const socat = ['socat', `pty,raw,echo=0,link=${a}`, `pty,raw,echo=0,link=${b}`];
  const [command, ...args] = fs.existsSync(SETPRIV)
    ? [SETPRIV, '--pdeathsig', 'KILL', '--', ...socat]
    : socat;
  const child: ChildProcess = spawn(command!, args, { stdio: 'ignore' });
  // Whatever ends this process (an error, a second Ctrl-C), socat does not outlive it.
  const killOnExit = () => child.kill('SIGKILL');
  process.once('exit', killOnExit);
  const exited = new Promise<void>((resolve) => {
    child.once('exit', () => resolve());
    child.once('error', () => resolve());
  });
  const stop = async () => {
    process.removeListener('exit', killOnExit);
    if (child.exitCode === null && child.signalCode === null) child.kill('SIGTERM');
    await exited;
  };
  const missing = 'socat is not installed (apt install socat, brew install socat; or --no-so101)';
  const failed = new Promise<string>((resolve) => {
    child.once('error', (err: NodeJS.ErrnoException) =>
      resolve(err.code === 'ENOENT' ? missing : `socat: ${err.message}`),
    );
    // 127: setpriv found no socat to run.
    child.once('exit', (code, signal) =>
      resolve(code === 127 ? missing : `socat exited (${signal ?? `code ${code}`})`),
    );
  });
  const deadline = Date.now() + timeoutMs;
  let why: string | undefined;
  void failed.then((w) => (why = w));
  while (!(fs.existsSync(a) && fs.existsSync(b))) {
    if (why !== undefined || Date.now() > deadline) {
      await stop();
      throw new Error(why ?? `socat made no pty pair in ${timeoutMs} ms`);
    }
    await new Promise((r) => setTimeout(r, 20));
  }
  return { stop };
}
