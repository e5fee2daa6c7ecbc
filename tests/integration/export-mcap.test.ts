/**
 * `armtwin export` against a real influxd (1.8): known points in (µs time stamps, positions,
 * health, commands, IK outcomes, another arm, a point on the range's end), an MCAP file out,
 * read back with Foxglove's own Python `mcap` library (tests/helpers/mcap_check.py). Every
 * stored point of the arm and range is one message with its exact time and fields, compared with
 * what InfluxDB returns for InfluxQL (not the Flux the exporter uses); joint states and link
 * transforms follow the armtwin5 profile and URDF, and the tip they put the arm's hand at is
 * where the §4 forward kinematics puts it. CSV holds the same rows; bad input is refused.
 */
import { execFile } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { createHistoryHandler, historyReader } from '@armtwin/middleware/history';
import { forwardKinematics, jointsFromServoAngles, type Quad } from '@armtwin/ik';
import { angleFromPwm } from '@armtwin/protocol';
import { influxCliEnv, influxQuery } from '../helpers/influx.ts';
import { REPO_ROOT } from '../helpers/files.ts';
import { servoSdkPython } from '../helpers/servo-sdk-python.ts';
import { useInflux } from '../helpers/use-services.ts';
import { ARMTWIN } from './sim-helpers.ts';

const run = promisify(execFile);
const influx = useInflux();

const ARM = 'exp1';
const T0_US = Date.UTC(2026, 10, 24, 6, 0, 0) * 1000;
const FROM = '2026-11-24T06:00:00Z';
const TO = '2026-11-24T06:00:05Z';
const SERVOS = 6;
/** Position groups at 20 Hz for 5 s, with a µs offset that a millisecond clock would lose. */
const GROUPS = 100;
const pwmAt = (k: number, id: number) => 1500 + Math.round(400 * Math.sin(k / 15 + id));

function lines(): string[] {
  const out: string[] = [];
  for (let k = 0; k < GROUPS; k++) {
    const t = T0_US + k * 50_000 + 123;
    for (let id = 0; id < SERVOS; id++) {
      const pwm = pwmAt(k, id);
      out.push(`servo,arm=${ARM},id=00${id} pwm=${pwm}i,angle=${angleFromPwm(pwm)} ${t}`);
    }
  }
  for (let k = 0; k < 10; k++)
    for (let id = 0; id < SERVOS; id++)
      out.push(
        `servo,arm=${ARM},id=00${id} temp=${30 + id + k / 4},volt=7.${k} ${T0_US + k * 500_000 + 7}`,
      );
  out.push(`command,arm=${ARM},id=001 pwm=1800i,angle=40.5,ms=500i ${T0_US + 1_000_000}`);
  out.push(`command,arm=${ARM},id=004 angle=350,ms=800i ${T0_US + 2_000_000}`);
  out.push(`ik,arm=${ARM} code=0i,x=150,y=0,z=80,a=-90 ${T0_US + 1_500_000}`);
  out.push(`ik,arm=${ARM} code=2i,x=900,y=0,z=80,a=0 ${T0_US + 2_500_000}`);
  // Not in the export: another arm, and a point at the range's end (excluded).
  out.push(`servo,arm=other,id=000 pwm=1500i,angle=0 ${T0_US + 1_000_000}`);
  out.push(`servo,arm=${ARM},id=000 pwm=1500i,angle=0 ${T0_US + 5_000_000}`);
  // One control event (docs/protocol.md § Control), as the middleware stores arm/{id}/audit.
  out.push(
    `audit,arm=${ARM},kind=refused-command by="bob",detail="controlled by alice" ${T0_US + 77}`,
  );
  return out;
}

interface Checked {
  library: string;
  header_library: string;
  message_count: number;
  topics: Record<string, { schema: string; encoding: string; count: number }>;
  records: [string, string, Record<string, unknown>][];
  tf_sizes: number[];
  last_joint_states?: { joints: { name: string; position: number }[] };
  tip?: { root: string; position: [number, number, number] };
}

/** InfluxQL's rows of one measurement, nanosecond times, as [time, tags+fields]. */
async function influxRows(measurement: string): Promise<Record<string, unknown>[]> {
  const { url, db } = influx();
  const body = (await influxQuery(
    url,
    `SELECT * FROM "${db}"."autogen"."${measurement}" WHERE "arm" = '${ARM}' AND time >= '${FROM}' AND time < '${TO}'`,
  )) as { results: { series?: { columns: string[]; values: unknown[][] }[] }[] };
  const series = body.results[0]?.series?.[0];
  if (!series) return [];
  return series.values.map((v) => Object.fromEntries(series.columns.map((c, i) => [c, v[i]])));
}

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-export-'));
const env = () => influxCliEnv(influx());
const exportTo = (file: string, ...extra: string[]) =>
  run(
    process.execPath,
    [ARMTWIN, 'export', '--arm', ARM, '--from', FROM, '--to', TO, '--out', file, ...extra],
    { cwd: REPO_ROOT, env: env(), timeout: 60_000 },
  );

beforeAll(async () => {
  const res = await fetch(`${influx().url}/write?db=${influx().db}&precision=u`, {
    method: 'POST',
    body: lines().join('\n'),
  });
  expect(res.status).toBe(204);
});

afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

describe("armtwin export --format mcap, read back with Foxglove's mcap library", () => {
  let checked: Checked;
  let stderr = '';

  beforeAll(async () => {
    const file = path.join(dir, 'exp1.mcap');
    ({ stderr } = await exportTo(file, '--profile', 'armtwin5'));
    const { stdout } = await run(
      servoSdkPython(),
      [path.join(REPO_ROOT, 'tests/helpers/mcap_check.py'), file, 'tip'],
      { maxBuffer: 64 * 1024 * 1024 },
    );
    checked = JSON.parse(stdout) as Checked;
  });

  test('the command says what it wrote', () => {
    expect(stderr).toContain(`${GROUPS * SERVOS + 10 * SERVOS} servo, 2 command and 2 ik points`);
  });

  test("one message per stored point, with the point's exact time and fields", async () => {
    const expected: [string, string, Record<string, unknown>][] = [];
    for (const m of ['servo', 'command', 'ik'] as const)
      for (const row of await influxRows(m)) {
        const { time, arm, id, ...fields } = row as { time: string; arm: string; id?: string };
        expect(arm).toBe(ARM);
        const ns = BigInt(Date.parse(time.replace(/\.\d+Z$/, 'Z'))) * 1_000_000n + fracNs(time);
        const present = Object.fromEntries(Object.entries(fields).filter(([, v]) => v !== null));
        const topic = m === 'ik' ? `/arm/${ARM}/ik` : `/arm/${ARM}/${m}/${id}`;
        expected.push([topic, String(ns), { ...(id ? { id } : {}), ...present }]);
      }
    expect(expected.length).toBe(GROUPS * SERVOS + 10 * SERVOS + 4);
    // Not stored points: the control log and the commanded targets drawn from the commands.
    const derived = [`/${ARM}/log`, `/${ARM}/targets`];
    const got = checked.records
      .filter(([topic]) => !derived.includes(topic))
      .map(([topic, ns, { timestamp, ...data }]) => {
        const t = timestamp as { sec: number; nsec: number };
        expect(BigInt(t.sec) * 1_000_000_000n + BigInt(t.nsec)).toBe(BigInt(ns));
        return [topic, ns, data] as [string, string, Record<string, unknown>];
      });
    const key = (r: [string, string, unknown]) => `${r[1]} ${r[0]}`;
    expect([...got].sort((a, b) => key(a).localeCompare(key(b)))).toEqual(
      [...expected].sort((a, b) => key(a).localeCompare(key(b))),
    );
    // the µs survive: a millisecond clock would have lost the 123
    expect(got.some(([, ns]) => BigInt(ns) % 1_000_000n === 123_000n)).toBe(true);
  });

  test('the control event is a foxglove.Log message at its own time', () => {
    expect(checked.topics[`/${ARM}/log`]).toMatchObject({ schema: 'foxglove.Log', count: 1 });
    const [, ns, data] = checked.records.find(([topic]) => topic === `/${ARM}/log`)!;
    expect(BigInt(ns)).toBe(BigInt(T0_US + 77) * 1000n);
    expect(data).toMatchObject({
      level: 3, // WARNING: a refused move
      message: 'controlled by alice',
      name: 'refused-command by bob',
    });
  });

  test('topics, schemas and counts: per servo, commands, IK, joint states and transforms', () => {
    const t = checked.topics;
    for (let id = 0; id < SERVOS; id++)
      expect(t[`/arm/${ARM}/servo/00${id}`]).toEqual({
        schema: 'armtwin.ServoSample',
        encoding: 'json',
        count: GROUPS + 10,
      });
    expect(t[`/arm/${ARM}/command/001`]?.count).toBe(1);
    expect(t[`/arm/${ARM}/command/004`]?.count).toBe(1);
    expect(t[`/arm/${ARM}/ik`]).toMatchObject({ schema: 'armtwin.IkResult', count: 2 });
    expect(t[`/${ARM}/joint_states`]).toMatchObject({
      schema: 'foxglove.JointStates',
      count: GROUPS,
    });
    expect(t[`/${ARM}/tf`]).toMatchObject({ schema: 'foxglove.FrameTransforms', count: GROUPS });
    expect(t[`/${ARM}/robot_description`]).toEqual({
      schema: 'std_msgs/String',
      encoding: 'json',
      count: 1,
    });
    expect(t[`/${ARM}/targets`]).toMatchObject({
      schema: 'armtwin.JointTargets',
      count: 2,
    });
    expect(Object.keys(t).some((k) => k.includes('other'))).toBe(false);
    const total = Object.values(t).reduce((n, x) => n + x.count, 0);
    expect(checked.message_count).toBe(total);
    expect(checked.header_library).toBe('armtwin export');
  });

  test('the transforms put the hand where the §4 forward kinematics does', () => {
    const k = GROUPS - 1;
    const s = [0, 1, 2, 3].map((id) => angleFromPwm(pwmAt(k, id))) as Quad;
    const fk = forwardKinematics(jointsFromServoAngles(s));
    expect(checked.tip?.root).toBe('base_link');
    const [x, y, z] = checked.tip!.position.map((v) => v * 1000);
    expect(x).toBeCloseTo(fk.x, 3);
    expect(y).toBeCloseTo(fk.y, 3);
    expect(z).toBeCloseTo(fk.z, 3);
    expect(checked.last_joint_states?.joints.map((j) => j.name)).toEqual([
      'base_yaw',
      'shoulder',
      'elbow',
      'wrist_pitch',
      'wrist_roll',
      'gripper',
    ]);
  });
});

describe("the history API's download: GET /history/export", () => {
  let base = '';
  let server: http.Server;

  beforeAll(async () => {
    const handler = createHistoryHandler({
      // Flux here; the command above reads through InfluxQL (the default): both languages export.
      reader: historyReader(
        { url: influx().url, token: '', org: '', bucket: influx().bucket, timeoutMs: 60_000 },
        'flux',
      ),
    });
    server = http.createServer((req, res) => {
      void handler(req, res).then((done) => done || res.writeHead(404).end());
    });
    await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
    base = `http://127.0.0.1:${(server.address() as AddressInfo).port}`;
  });
  afterAll(() => new Promise<void>((r) => server.close(() => r())));

  test("the same MCAP as the command: an attachment that Foxglove's library reads", async () => {
    const res = await fetch(
      `${base}/history/export?arm=${ARM}&start=${FROM}&stop=${TO}&format=mcap&profile=armtwin5`,
    );
    expect(res.status).toBe(200);
    expect(res.headers.get('content-disposition')).toMatch(
      /^attachment; filename="exp1-.*\.mcap"$/,
    );
    const file = path.join(dir, 'download.mcap');
    fs.writeFileSync(file, Buffer.from(await res.arrayBuffer()));
    const { stdout } = await run(
      servoSdkPython(),
      [path.join(REPO_ROOT, 'tests/helpers/mcap_check.py'), file],
      { maxBuffer: 64 * 1024 * 1024 },
    );
    const c = JSON.parse(stdout) as Checked;
    // + the control event, the robot description, a joint target per command instant (2)
    expect(c.message_count).toBe(GROUPS * SERVOS + 10 * SERVOS + 4 + 2 * GROUPS + 1 + 1 + 2);
  });

  test('bad parameters are refused by name before anything is sent', async () => {
    for (const [q, parameter] of [
      ['format=pdf', 'format'],
      ['profile=nosuch', 'profile'],
      ['profile=..%2Fetc', 'profile'],
    ] as const) {
      const res = await fetch(`${base}/history/export?arm=${ARM}&start=${FROM}&stop=${TO}&${q}`);
      expect(res.status).toBe(400);
      expect(((await res.json()) as { parameter: string }).parameter).toBe(parameter);
    }
  });
});

/** The nanoseconds after the second of an RFC 3339 time. */
function fracNs(time: string): bigint {
  const m = /\.(\d+)Z$/.exec(time);
  return m ? BigInt(m[1]!.padEnd(9, '0')) : 0n;
}

describe('armtwin export --format csv and bad input', () => {
  test('CSV: a header and one row per stored point, in time order', async () => {
    const file = path.join(dir, 'exp1.csv');
    await exportTo(file, '--format', 'csv');
    const rows = fs.readFileSync(file, 'utf8').trimEnd().split('\n');
    expect(rows[0]).toBe('time,measurement,id,pwm,angle,temp,volt,ms,code,x,y,z,a');
    expect(rows).toHaveLength(1 + GROUPS * SERVOS + 10 * SERVOS + 4);
    expect(rows[1]).toBe('2026-11-24T06:00:00.000007000Z,servo,000,,,30,7,,,,,,');
    expect(rows).toContain(
      `2026-11-24T06:00:00.000123000Z,servo,000,${pwmAt(0, 0)},${angleFromPwm(pwmAt(0, 0))},,,,,,,,`,
    );
    expect(rows.filter((r) => r.includes(',ik,'))).toEqual([
      '2026-11-24T06:00:01.500000000Z,ik,,,,,,,0,150,0,80,-90',
      '2026-11-24T06:00:02.500000000Z,ik,,,,,,,2,900,0,80,0',
    ]);
  });

  test('a time that is not ISO 8601 is refused, naming the flag', async () => {
    const err = await exportTo(path.join(dir, 'x.mcap'), '--from', 'yesterday').catch(
      (e: { code: number; stderr: string }) => e,
    );
    expect(err).toMatchObject({ code: 1 });
    expect((err as { stderr: string }).stderr).toContain('--from must be an ISO 8601 time');
  });

  test('an unknown profile is refused with the profiles there are', async () => {
    const err = await exportTo(path.join(dir, 'y.mcap'), '--profile', 'nosuch').catch(
      (e: { code: number; stderr: string }) => e,
    );
    expect((err as { stderr: string }).stderr).toMatch(/no profile "nosuch".*armtwin5/);
  });
});
