/**
 * The controller's behaviour, the same on every driver (@armtwin/controller): one suite, run
 * against each row of `DRIVERS` through a real Mosquitto. Today's rows: the simulated servos
 * (`armtwin sim`) and the servo-bus gateway (`armtwin gateway --bus dynamixel`) driving an
 * emulated Dynamixel bus (`armtwin sim --bus dynamixel --serial`) over a socat pty pair, and a
 * ROS 2 arm (`armtwin gateway --ros2`, real rclpy and FastDDS, the arm a test node that executes
 * JointTrajectory as a joint_trajectory_controller would). LeRobot is a client of the
 * controller, not a driver: its plugin sends commands over MQTT like any operator
 * (tests/integration/lerobot-plugin.test.ts). On each: a motion request executes; a move into a keep-out
 * zone is refused, audited, and moves nothing; one operator at a time, handed over by a grant;
 * the deadman holds a moving arm when the operator's lease lapses; `#255PDST!` holds it at once.
 * Also an LSC board (`armtwin gateway`, the firmware being `armtwin sim --serial` on a socat
 * pty): the controller core checks in front of the firmware, which executes what passes itself;
 * the firmware is given the same arm without the zone, so the refusal is the gateway's.
 * The profile is armtwin5 with a table-top keep-out zone, written to a temporary models folder;
 * every driver reports servo angles (§8), so one reading of the status stream serves all.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { parseAudit, type AuditEvent } from '@armtwin/protocol';
import { MODELS_DIR } from '@armtwin/sim';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';
import { serialLine, type SerialLine } from './serial-line.ts';
import { startTestArm, testDomain } from '../helpers/ros2.ts';

const broker = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-behaviour-'));
const MODELS = path.join(dir, 'models');
const PROFILE = 'behaviour5';
/** The same arm without the zone: what the LSC board's firmware knows. */
const BARE = 'behaviour5-bare';
const SERVOS = 6;
const LEASE_MS = '1000';
/** A table in front of the arm: the hand must not enter it. */
const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
const profileArgs = ['--profile', PROFILE, '--models', MODELS];

beforeAll(() => {
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  ) as Record<string, unknown>;
  fs.mkdirSync(path.join(MODELS, PROFILE), { recursive: true });
  fs.writeFileSync(
    path.join(MODELS, PROFILE, 'profile.json'),
    JSON.stringify({ ...raw, name: PROFILE, keepOut: { zones: [TABLE] } }),
  );
  fs.mkdirSync(path.join(MODELS, BARE), { recursive: true });
  fs.writeFileSync(path.join(MODELS, BARE, 'profile.json'), JSON.stringify({ ...raw, name: BARE }));
});

afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

/** A driver under test: started for arm `arm` on the broker at `url`. */
interface DriverRow {
  name: string;
  start(url: string, arm: string): Promise<Driver>;
}

/** A started driver: stopped after its tests; its output, to say why it did not come online. */
interface Driver {
  stop(): Promise<unknown>;
  output?(): string;
}

/**
 * `armtwin gateway --serial` (with `gatewayArgs`) for arm `arm`, the device on the far side of a
 * socat pty pair being `armtwin <deviceArgs>` (it says `ready` once up).
 */
async function gatewayOnLine(
  url: string,
  arm: string,
  deviceArgs: (armSide: string) => string[],
  ready: string,
  gatewayArgs: string[],
): Promise<Driver> {
  const host = path.join(dir, `${arm}-gateway`);
  const line: SerialLine = serialLine(host, path.join(dir, `${arm}-arm`), deviceArgs, ready);
  await line.start();
  const gateway: Child = armtwin([
    ...['gateway', '--serial', host, ...gatewayArgs, ...profileArgs],
    ...['--mqtt', url, '--arm', arm, '--operator-lease', LEASE_MS],
  ]);
  return {
    async stop() {
      await gateway.stop('SIGKILL');
      await line.stop();
    },
    output: () => gateway.output(),
  };
}

const DRIVERS: DriverRow[] = [
  {
    name: 'the simulated servos (armtwin sim)',
    async start(url, arm) {
      const sim = armtwin([
        'sim',
        ...['--mqtt', url, '--arm', arm, '--rate', '50', '--report', 'angle'],
        ...['--operator-lease', LEASE_MS, ...profileArgs],
      ]);
      return { stop: () => sim.stop('SIGKILL') };
    },
  },
  {
    name: 'the servo bus (armtwin gateway --bus dynamixel)',
    start: (url, arm) =>
      gatewayOnLine(
        url,
        arm,
        (armSide) => [
          ...['sim', '--bus', 'dynamixel', '--serial', armSide, '--baud', '1000000'],
          ...profileArgs,
        ],
        'simulated servo bus on the serial line',
        ['--bus', 'dynamixel', '--baud', '1000000'],
      ),
  },
  {
    name: 'an LSC board (armtwin gateway, firmware on a serial line)',
    start: (url, arm) =>
      gatewayOnLine(
        url,
        arm,
        (armSide) => [
          ...['sim', '--serial', armSide, '--rate', '50', '--report', 'angle'],
          ...['--profile', BARE, '--models', MODELS],
        ],
        'simulated controller on the serial line',
        [],
      ),
  },
  {
    name: 'a ROS 2 arm (armtwin gateway --ros2)',
    async start(url, arm) {
      // The arm's trajectory controller: a rclpy node executing JointTrajectory (no ros2_control here).
      const domain = String(testDomain());
      const rosArm = await startTestArm([
        ...['--joints', 'base_yaw,shoulder,elbow,wrist_pitch,wrist_roll,gripper'],
        ...['--domain', domain, '--rate', '50'],
      ]);
      const gateway: Child = armtwin([
        'gateway',
        ...['--ros2', '--domain', domain, ...profileArgs],
        ...['--mqtt', url, '--arm', arm, '--operator-lease', LEASE_MS],
      ]);
      return {
        async stop() {
          await gateway.stop('SIGKILL');
          await rosArm.stop();
        },
      };
    },
  },
];

describe.each(DRIVERS.map((d, i) => ({ ...d, arm: `behaviour-${i}` })))(
  'the controller on $name',
  ({ start, arm }) => {
    let driver: Driver | undefined;
    let w: StatusWatcher;
    let users: MqttClient;
    const feedback: { id?: string; status?: string; message?: string }[] = [];
    const audit: AuditEvent[] = [];
    let holder = '';

    /** Servo `id`'s angle in every state group after item `from`. */
    const angles = (id: number, from = 0) => w.angles(id, from, SERVOS);
    const reaches = (id: number, deg: number, from: number) =>
      w.until(
        () => (angles(id, from).some((d) => Math.abs(d - deg) < 0.1) ? true : undefined),
        15_000,
        `servo ${id} at ${deg}°`,
      );
    /** The angle servo `id` stays at for 25 state groups in a row, after item `from`. */
    const stillAt = (id: number, from: number) =>
      w.until(
        () => {
          const recent = angles(id, from).slice(-25);
          return recent.length === 25 && new Set(recent).size === 1 ? recent[0] : undefined;
        },
        15_000,
        `servo ${id} to rest`,
      );
    const error = (test: (text: string) => boolean, from: number) =>
      w.frame((f) => f.type === 'controllerError' && test(f.text), from, 15_000);
    const event = (test: (e: AuditEvent) => boolean, what: string) =>
      w.until(() => audit.find(test), 15_000, what);
    const say = (topic: string, payload: string) =>
      users.publishAsync(`arm/${arm}/${topic}`, payload, { qos: 1 });
    /** Every servo to 0° and at rest there (the same start on every driver). */
    async function home() {
      const from = w.items.length;
      await w.send(
        `{${Array.from({ length: SERVOS }, (_, i) => `#00${i}A+000.00T0300!`).join('')}}`,
      );
      for (let i = 0; i < SERVOS; i++) await reaches(i, 0, from);
    }

    beforeAll(async () => {
      const url = broker().url;
      w = await StatusWatcher.connect(url, arm);
      users = await mqtt.connectAsync(url);
      users.on('message', (topic, payload) => {
        const kind = topic.split('/')[2];
        if (kind === 'feedback') feedback.push(JSON.parse(payload.toString()) as never);
        if (kind === 'holder')
          holder = (JSON.parse(payload.toString()) as { user: string | null }).user ?? '';
        const e = kind === 'audit' ? parseAudit(payload) : null;
        if (e) audit.push(e);
      });
      await users.subscribeAsync([`arm/${arm}/feedback`, `arm/${arm}/holder`, `arm/${arm}/audit`], {
        qos: 1,
      });
      driver = await start(url, arm);
      await w
        .until(
          () => (w.retained.get(`arm/${arm}/online`) === '1' ? true : undefined),
          30_000,
          `${arm} online`,
        )
        .catch((err: Error) => {
          throw new Error(`${err.message}\n${driver?.output?.() ?? ''}`);
        });
      await w.until(() => (angles(0).length >= 5 ? true : undefined), 15_000, 'state groups');
    });

    afterAll(async () => {
      await driver?.stop();
      await users?.endAsync(true);
      await w?.close();
    });

    test('a motion request executes: planned, done, and the arm at its target', async () => {
      await home();
      const from = w.items.length;
      const id = `${arm}-joint`;
      const request = { id, mode: 'joint', targets: [{ servos: { '000': 1800 } }], execute: true };
      await say('request', JSON.stringify(request));
      const done = await w.until(
        () =>
          feedback.find((f) => f.id === id && f.status !== 'planned' && f.status !== 'executing'),
        30_000,
        'the request to end',
      );
      expect(done, JSON.stringify(done)).toMatchObject({ status: 'done' });
      await reaches(0, 40.5, from); // 1800 µs = +40.5° through the profile (§2)
    });

    test('a move into a keep-out zone is refused, audited, and nothing moves', async () => {
      await home();
      const from = w.items.length;
      await w.send('{#001A-045.00T0500!#002A-045.00T0500!#003A-090.00T0500!}');
      const refused = await error((t) => t.startsWith('group rejected: zone:'), from);
      expect(refused.frame).toMatchObject({
        text: expect.stringMatching(/^group rejected: zone: hand in "table"( on the way)?$/),
      });
      await event(
        (e) => e.kind === 'refused-keep-out' && e.detail.includes('"table"'),
        'the refusal in the audit record',
      );
      expect(await stillAt(1, from)).toBe(0);
    });

    test('one operator at a time: the holder moves the arm, a grant hands it over', async () => {
      await home();
      await say('claim/alice', 'take');
      await w.until(() => (holder === 'alice' ? true : undefined), 15_000, 'alice holding');
      const taken = w.items.length;
      await say('control/alice', '#000A+020.00T0200!');
      await reaches(0, 20, taken);
      const refusedAt = w.items.length;
      await say('control/bob', '#000A-020.00T0200!');
      await error((t) => t.includes('controlled by alice'), refusedAt);
      await event((e) => e.kind === 'refused-command' && e.by === 'bob', 'bob refused');
      expect(await stillAt(0, refusedAt)).toBe(20);
      await say('claim/bob', 'ask');
      await say('claim/alice', 'grant bob');
      await w.until(() => (holder === 'bob' ? true : undefined), 15_000, 'bob holding');
      const granted = w.items.length;
      await say('control/bob', '#000A-020.00T0200!');
      await reaches(0, -20, granted);
      await say('claim/bob', 'release');
      await w.until(() => (holder === '' ? true : undefined), 15_000, 'nobody holding');
    });

    test('the deadman holds a moving arm when the operator stops beating', async () => {
      await home();
      const from = w.items.length;
      await say('operator', '1');
      await say('operator', '1'); // a beating operator: its lease now runs
      await w.send('#000A+090.00T9000!'); // 10°/s
      await w.until(
        () => (angles(0, from).some((d) => d > 3) ? true : undefined),
        15_000,
        'the base moving',
      );
      await error((t) => t === 'deadman stop', from); // no more beats: the lease lapses
      const held = await stillAt(0, from);
      expect(held).toBeGreaterThan(3);
      expect(held).toBeLessThan(60);
      await say('operator', '0');
    });

    test('#255PDST! holds the arm at once, short of a slow move, and is audited', async () => {
      await home();
      const from = w.items.length;
      await w.send('#000A+090.00T9000!');
      await w.until(
        () => (angles(0, from).some((d) => d > 3) ? true : undefined),
        15_000,
        'the base moving',
      );
      await w.send('#255PDST!');
      await event((e) => e.kind === 'e-stop', 'the e-stop in the audit record');
      const held = await stillAt(0, from);
      expect(held).toBeGreaterThan(3);
      expect(held).toBeLessThan(60);
    });
  },
);
