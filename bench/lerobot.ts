/**
 * LeRobot (issue 30): a LeRobot control loop at 30 and 60 Hz, LeRobot 0.6.1's own robot API
 * (`get_observation()` + `send_action()` each iteration, paced by its `precise_sleep`;
 * bench/lerobot/control_loop.py), on the same emulated SO-101 bus (`armtwin sim --bus feetech`
 * on a socat pty pair, six STS3215 at 1 Mbaud) two ways in the same run:
 * - direct: LeRobot's own SO101Follower (its FeetechMotorsBus) on the bus's pty;
 * - through armtwin: armtwin's LeRobot plugin (`--robot.type=armtwin`) → MQTT (this run's
 *   Mosquitto) → the bus gateway's controller core (lease, limits, zones) → the same bus, its
 *   positions read at the gateway's default 50 Hz and reported on MQTT.
 * The action sweeps shoulder_pan to and fro by 0.5° an iteration (±10°); latency is action sent →
 * the loop's first observation at that goal or past it (within 0.15°; the loop reads observations
 * 2 ms apart while it waits, which LeRobot's loop would sleep through); the 4 actions after each
 * turn of the sweep are not scored, and a goal not reached in 0.5 s counts as unreached. Overruns: iterations whose get_observation +
 * send_action took longer than the period (LeRobot's loop is late by that much).
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { lerobotPython, lerobotVenv, PLUGIN_DIR } from '../tests/helpers/lerobot-python.ts';
import { so101BusLine } from '../tests/integration/serial-line.ts';
import { spawnChild, type Child } from './lib/proc.ts';
import type { MqttClient } from 'mqtt';
import { connectMqtt, REPO, waitOnline } from './lib/stack.ts';
import { round, summarize } from './lib/stats.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const ARMTWIN = path.join(REPO, 'apps', 'cli', 'bin', 'armtwin.mjs');
const LOOP = path.join(REPO, 'bench', 'lerobot', 'control_loop.py');
const RATES = [30, 60] as const;
const LOOP_SETTINGS = {
  step: 0.5,
  amplitude: 10,
  tolerance: 0.15,
  probe_ms: 2,
  window_s: 0.5,
  settle: 4,
};

interface LoopResult {
  iterations: number;
  overruns: number;
  late_ms: number[];
  latency_ms: number[];
  unreached: number;
  scored: number;
  read_errors: number;
  observations: number;
}

/** A socat pty pair with the emulated SO-101 bus on one end; `host` is the other. */
async function emulatedBus(name: string): Promise<{ host: string; stop(): Promise<void> }> {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-bench-lerobot-'));
  const line = so101BusLine(dir, name);
  await line.start();
  return {
    host: line.hostSide,
    async stop() {
      await line.stop();
      fs.rmSync(dir, { recursive: true, force: true });
    },
  };
}

/** One control loop (control_loop.py) to its end; its JSON result. */
async function loop(
  ctx: BenchContext,
  name: string,
  req: Record<string, unknown>,
): Promise<LoopResult> {
  const log = path.join(ctx.logDir, `lerobot-${name}.log`);
  const child = spawnChild(lerobotPython('lerobot, paho.mqtt'), [LOOP, JSON.stringify(req)], {
    cwd: REPO,
    logFile: log,
    stdout: 'pipe',
    env: { ...process.env, PYTHONPATH: PLUGIN_DIR },
  });
  let out = '';
  child.proc.stdout!.on('data', (d: Buffer) => (out += d.toString()));
  const code = await child.exited;
  if (code !== 0)
    throw new Error(`the ${name} loop exited ${code}: ${fs.readFileSync(log, 'utf8').slice(-400)}`);
  return JSON.parse(out) as LoopResult;
}

async function direct(ctx: BenchContext, fps: number, seconds: number): Promise<LoopResult> {
  const bus = await emulatedBus(`direct-${fps}`);
  const calibration = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-bench-lerobot-cal-'));
  try {
    return await loop(ctx, `direct-${fps}`, {
      mode: 'direct',
      port: bus.host,
      calibration_dir: calibration,
      fps,
      seconds,
      ...LOOP_SETTINGS,
    });
  } finally {
    await bus.stop();
    fs.rmSync(calibration, { recursive: true, force: true });
  }
}

async function throughArmtwin(
  ctx: BenchContext,
  fps: number,
  seconds: number,
): Promise<LoopResult & { errors: Record<string, number> }> {
  const bus = await emulatedBus(`armtwin-${fps}`);
  const arm = `lerobot-bench-${fps}`;
  let gateway: Child | undefined;
  let watcher: MqttClient | undefined;
  const errors: Record<string, number> = {};
  try {
    gateway = spawnChild(
      process.execPath,
      [
        ARMTWIN,
        'gateway',
        ...['--bus', 'feetech', '--serial', bus.host, '--baud', '1000000', '--profile', 'so101'],
        ...['--arm', arm, '--mqtt', ctx.broker.url],
      ],
      { cwd: REPO, logFile: path.join(ctx.logDir, `lerobot-gateway-${fps}.log`) },
    );
    await waitOnline(ctx.broker.url, arm);
    // What the gateway said went wrong ($ERR on status): a refused command, a late bus read.
    watcher = await connectMqtt(ctx.broker.url, `bench-lerobot-${fps}-${process.pid}`);
    watcher.on('message', (_t, p) => {
      for (const m of p.toString().matchAll(/\$ERR:([^!]*)!/g)) {
        const kind = m[1]!.replace(/^missing servos[\d ]+$/, 'missing servos (a bus read late)');
        errors[kind] = (errors[kind] ?? 0) + 1;
      }
    });
    await watcher.subscribeAsync(`arm/${arm}/status`, { qos: 0 });
    const r = await loop(ctx, `armtwin-${fps}`, {
      mode: 'armtwin',
      broker: ctx.broker.url,
      arm,
      fps,
      seconds,
      ...LOOP_SETTINGS,
    });
    return { ...r, errors };
  } finally {
    await watcher?.endAsync();
    await gateway?.stop();
    await bus.stop();
  }
}

const ms = (v: number) => fmt(v, 1);
const describe = (r: LoopResult) => {
  const s = summarize(r.latency_ms);
  return {
    text: `${ms(s.p50)} / ${ms(s.p99)} ms; overruns ${r.overruns}/${r.iterations}; unreached ${r.unreached}/${r.scored}`,
    s,
  };
};
const summary = (r: LoopResult) => {
  const { latency_ms, late_ms, ...rest } = r;
  const s = summarize(latency_ms);
  const late = summarize(late_ms);
  return {
    ...rest,
    latency_ms: { n: s.n, p50: round(s.p50, 2), p99: round(s.p99, 2), max: round(s.max, 2) },
    late_ms: { n: late.n, p50: round(late.p50, 2), max: round(late.max, 2) },
  };
};

export const lerobotSection: Section = {
  id: 'lerobot',
  title: 'LeRobot: its control loop through armtwin against the bus directly',
  precheck() {
    try {
      lerobotPython('lerobot, paho.mqtt');
      execFileSync('socat', ['-V'], { stdio: 'ignore' });
      return null;
    } catch (err) {
      return (err as Error).message;
    }
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const seconds = ctx.quick ? 10 : 60;
    const loadBefore = os.loadavg().map((v) => round(v, 2));
    const rows: Row[] = [];
    const perRate: Record<string, unknown> = {};
    for (const fps of RATES) {
      ctx.log(`lerobot: ${seconds} s at ${fps} Hz, on the bus directly`);
      const d = await direct(ctx, fps, seconds);
      ctx.log(`lerobot: ${seconds} s at ${fps} Hz, through armtwin`);
      const a = await throughArmtwin(ctx, fps, seconds);
      const dd = describe(d);
      const aa = describe(a);
      perRate[fps] = { direct: summary(d), armtwin: summary(a) };
      rows.push({
        figure: `LeRobot loop at ${fps} Hz through armtwin: action sent → position reported p50 / p99; overruns`,
        value: `${aa.text}; $ERR ${
          Object.entries(a.errors)
            .map(([k, n]) => `${k} ×${n}`)
            .join(', ') || 'none'
        }`,
        baseline: `on the bus directly (SO101Follower): ${dd.text}`,
        target: `added p50 ${ms(aa.s.p50 - dd.s.p50)} ms, p99 ${ms(aa.s.p99 - dd.s.p99)} ms (reported)`,
        met: null,
      });
    }
    return {
      rows,
      settings: {
        seconds,
        rates: RATES,
        ...LOOP_SETTINGS,
        bus: 'armtwin sim --bus feetech --profile so101, socat pty, 1 Mbaud',
        gatewayStateRateHz: 50,
        lerobot: '0.6.1 (reply allowance 500 ms, as in lerobot-plugin.test.ts)',
        venv: lerobotVenv(),
      },
      data: {
        perRate,
        loadAverage: { before: loadBefore, after: os.loadavg().map((v) => round(v, 2)) },
      },
    };
  },
};
