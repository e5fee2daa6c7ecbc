/**
 * LeRobot drives the arm through armtwin: LeRobot 0.6.1's own teleoperate and record commands
 * (their python functions, as `lerobot-teleoperate` / `lerobot-record` run them) with
 * `--robot.type=armtwin`, the plugin of packages/lerobot/python found by LeRobot's own
 * register_third_party_plugins, and LeRobot's SO-101 leader (so101_leader, its FeetechMotorsBus)
 * on an emulated Feetech bus (`armtwin sim --bus feetech` over a socat pty pair) as the
 * teleoperator. The follower is a simulated SO-101 (`armtwin sim --profile so101`) with a
 * keep-out zone, through a real Mosquitto. The emulated leader cannot be moved by hand, so each
 * session sets where it stands by its shoulder_pan homing offset. Shown: the follower goes where
 * the leader is and LeRobot's dataset records it; a leader pose through the zone is refused and
 * the follower stays; an emergency stop from someone else wins over LeRobot's lease, and the arm
 * stays stopped for the rest of the session.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { parseAudit, type AuditEvent } from '@armtwin/protocol';
import { lerobotPython, PLUGIN_DIR, startPluginScript } from '../helpers/lerobot-python.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { startSo101Follower } from './so101-follower.ts';
import { StatusWatcher, type Child } from './sim-helpers.ts';
import { so101BusLine } from './serial-line.ts';

const broker = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-lerobot-plugin-'));
const MODELS = path.join(dir, 'models');
const ARM = 'follower';
const MOTORS = ['shoulder_pan', 'shoulder_lift', 'elbow_flex', 'wrist_flex', 'wrist_roll'];

/** The leader's calibration as LeRobot writes it: a full turn, zero homing but shoulder_pan's. */
const leaderCalibration = (panOffset: number) =>
  Object.fromEntries(
    [...MOTORS, 'gripper'].map((m, i) => [
      m,
      {
        id: i + 1,
        drive_mode: 0,
        homing_offset: i === 0 ? panOffset : 0,
        range_min: 0,
        range_max: 4095,
      },
    ]),
  );
/** LeRobot's degrees of a leader whose shaft is at mid-turn (2048) with this homing offset. */
const leaderPan = (panOffset: number) => ((2048 - panOffset - 2047.5) * 360) / 4095;

let follower: Child;
let w: StatusWatcher;
const audit: AuditEvent[] = [];
const pan = (from = 0) => w.angles(1, from);

beforeAll(async () => {
  follower = startSo101Follower(broker().url, ARM, MODELS);
  w = await StatusWatcher.connect(broker().url, ARM);
  w.client.on('message', (topic, payload) => {
    const e = topic === `arm/${ARM}/audit` ? parseAudit(payload.toString()) : undefined;
    if (e) audit.push(e);
  });
  await w.client.subscribeAsync(`arm/${ARM}/audit`, { qos: 1 });
  await w.online();
});

afterAll(async () => {
  await w?.client.endAsync();
  await follower?.stop('SIGKILL');
  fs.rmSync(dir, { recursive: true, force: true });
});

let sessions = 0;
/** The dataset lerobot-record wrote through armtwin (the record test's). */
let recorded = '';
/**
 * One LeRobot session (`op` teleoperate or record, tests/helpers/lerobot/session_armtwin.py)
 * with the leader's shoulder_pan at `panOffset`; `during` runs while it does.
 */
async function session(
  op: 'teleoperate' | 'record',
  panOffset: number,
  extra: Record<string, unknown>,
  during: (ended: () => boolean) => Promise<void> = async () => {},
): Promise<{ code: number | null; out: string; err: string }> {
  const k = ++sessions;
  const line = so101BusLine(dir, `leader${k}`, {
    extra: ['--bus-fault', `field:1:homingOffset=${panOffset}`],
  });
  const host = line.hostSide;
  await line.start();
  try {
    const py = startPluginScript('session_armtwin.py', {
      op,
      broker: broker().url,
      arm: ARM,
      user: 'lerobot',
      leader_port: host,
      leader_calibration: leaderCalibration(panOffset),
      dir: path.join(dir, `session${k}`),
      fps: 30,
      ...extra,
    });
    try {
      await during(py.ended);
    } catch (e) {
      throw new Error(`${String(e)}; LeRobot said:\n${py.err().slice(-3000)}`, { cause: e });
    }
    return { code: await py.exited, out: py.out(), err: py.err() };
  } finally {
    await line.stop();
  }
}

const near = (a: number, b: number, tol = 0.5) => Math.abs(a - b) < tol;

describe('LeRobot through armtwin (lerobot_robot_armtwin)', () => {
  test("the plugin's pure part: its unittest suite passes on this clone's sources", () => {
    const out = execFileSync(
      lerobotPython('lerobot, paho.mqtt'),
      ['-m', 'unittest', 'discover', '-s', 'tests'],
      {
        cwd: PLUGIN_DIR,
        encoding: 'utf8',
        stdio: 'pipe',
      },
    );
    expect(out).toBe('');
  });

  test('lerobot-record: the follower goes where the leader is, and the dataset holds it', async () => {
    const from = w.items.length;
    const r = await session('record', 455, { time_s: 3 });
    recorded = path.join(dir, `session${sessions}`, 'dataset');
    expect(r.code, r.err).toBe(0);
    const target = leaderPan(455); // about -40°
    expect(pan(from).some((d) => near(d, target))).toBe(true);
    const ds = JSON.parse(r.out) as { frames: number; state: number[]; action: number[] };
    expect(ds.frames).toBeGreaterThan(10);
    expect(ds.action[0]).toBeCloseTo(target, 1); // the leader's shoulder_pan, LeRobot's degrees
    expect(ds.state[0]).toBeCloseTo(target, 0); // the follower's, as armtwin reported it
    expect(ds.state[5]).toBeCloseTo(50, 0); // the gripper at mid-range: 50 %, LeRobot's unit
    expect(audit.some((e) => e.kind === 'taken' && e.by === 'lerobot')).toBe(true);
    expect(audit.at(-1)).toMatchObject({ kind: 'released', by: 'lerobot' });
  }, 180_000);

  test('a leader pose through the keep-out zone is refused: the follower does not follow', async () => {
    const start = await w.until(() => pan().at(-1), 10_000, 'a position report');
    const from = w.items.length;
    const auditFrom = audit.length;
    const r = await session('teleoperate', -455, { time_s: 3 }); // the leader at about +40°
    expect(r.code, r.err).toBe(0);
    const refused = audit.slice(auditFrom).filter((e) => e.kind === 'refused-keep-out');
    expect(refused.length).toBeGreaterThan(0);
    expect(refused[0]!.by).toBe('lerobot');
    expect(r.err).toMatch(/armtwin refused a command/);
    expect(pan(from).every((d) => near(d, start))).toBe(true);
  }, 180_000);

  test("an emergency stop wins over LeRobot's lease, and the arm stays stopped", async () => {
    const start = await w.until(() => pan().at(-1), 10_000, 'a position report');
    const target = leaderPan(-284); // about +25°, 1° an action at most
    let stoppedAt = NaN;
    const auditFrom = audit.length;
    const r = await session(
      'teleoperate',
      -284,
      { time_s: 15, max_relative_target: 1 },
      async (ended) => {
        const from = w.items.length;
        await w.until(
          () => (pan(from).some((d) => d > start + 5) || ended() ? true : undefined),
          60_000,
          'the follower on its way',
        );
        await w.send('#255PDST!'); // someone else, on the plain control topic
        await w.until(
          () => (audit.slice(auditFrom).some((e) => e.kind === 'e-stop') ? true : undefined),
          5000,
          'the e-stop audited',
        );
        await new Promise((res) => setTimeout(res, 300)); // a state report after the stop
        stoppedAt = pan().at(-1)!;
      },
    );
    expect(r.code, r.err).toBe(0);
    expect(r.err).toMatch(/no action of this session moves the arm/);
    const after = pan(w.items.length - 10);
    expect(after.every((d) => near(d, stoppedAt))).toBe(true);
    expect(near(stoppedAt, target, 5)).toBe(false);
  }, 180_000);

  test("lerobot-replay: LeRobot's own replay of the recorded episode drives the follower back to its actions", async () => {
    expect(recorded, 'the record test ran first').not.toBe('');
    // Somewhere else first (nobody holds the arm now: the plain control topic moves it).
    await w.send('{#001A+010.00T0000!}');
    await w.until(
      () => (near(pan().at(-1) ?? NaN, 10) ? true : undefined),
      20_000,
      'the follower at +10°',
    );
    const from = w.items.length;
    const auditFrom = audit.length;
    const py = startPluginScript('replay_armtwin.py', {
      broker: broker().url,
      arm: ARM,
      user: 'lerobot-replay',
      repo_id: 'local/armtwin-so101',
      root: recorded,
      episode: 0,
      fps: 30,
    });
    expect(await py.exited, py.err().slice(-3000)).toBe(0);
    const ep = JSON.parse(py.out()) as { frames: number; first: number[]; last: number[] };
    expect(ep.frames).toBeGreaterThan(10);
    // The follower went from +10° to the episode's shoulder_pan (the leader's −40°), as replayed.
    expect(pan(from).some((d) => near(d, ep.last[0]!))).toBe(true);
    expect(
      audit.slice(auditFrom).some((e) => e.kind === 'taken' && e.by === 'lerobot-replay'),
    ).toBe(true);
    expect(audit.at(-1)).toMatchObject({ kind: 'released', by: 'lerobot-replay' });
  }, 180_000);
});
