/**
 * Motion requests (plans, poses, commands) on a real Mosquitto with two simulated arms as child processes
 * (`armtwin sim --profile armtwin5` and `--profile track6`): motion requests sent with the real
 * `mosquitto_pub` are planned and executed by the simulator, answered on `arm/{id}/feedback`,
 * and the status stream shows the target reached; plan-only moves nothing; unreachable and
 * malformed requests get the right status and code; each arm announces its profile and answers
 * only its own requests; pose checking pauses and re-plans around a stalled servo; an
 * emergency stop ends an execution.
 */
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const run = promisify(execFile);
const A5 = 'motion5';
const T6 = 'motion6';
const broker = useMosquitto();

interface Feedback {
  id: string | null;
  status: string;
  code: number;
  message: string;
  event?: string;
  field?: string;
  target?: number;
  step?: number;
  replans?: number;
  servo?: string;
  end?: Record<string, number>;
}

let sims: Child[] = [];
let w5: StatusWatcher;
let w6: StatusWatcher;
let fb: MqttClient;
const feedback: { arm: string; f: Feedback }[] = [];
const profiles = new Map<string, string>();
let n = 0;

beforeAll(async () => {
  const url = broker().url;
  w5 = await StatusWatcher.connect(url, A5);
  w6 = await StatusWatcher.connect(url, T6);
  fb = await mqtt.connectAsync(url);
  fb.on('message', (topic, payload) => {
    const [, arm, kind] = topic.split('/');
    if (kind === 'profile') profiles.set(arm!, payload.toString());
    else feedback.push({ arm: arm!, f: JSON.parse(payload.toString()) as Feedback });
  });
  await fb.subscribeAsync(['arm/+/feedback', 'arm/+/profile'], { qos: 1 });
  sims = [
    armtwin(['sim', '--mqtt', url, '--arm', A5, '--rate', '50']),
    armtwin(['sim', '--mqtt', url, '--arm', T6, '--rate', '50', '--profile', 'track6']),
  ];
  for (const [w, arm] of [
    [w5, A5],
    [w6, T6],
  ] as const)
    await w.until(
      () => (w.retained.get(`arm/${arm}/online`) === '1' ? true : undefined),
      30_000,
      `${arm} online`,
    );
});

afterAll(async () => {
  await Promise.all(sims.map((s) => s.stop('SIGKILL')));
  await w5?.close();
  await w6?.close();
  await fb?.endAsync(true);
});

/** Publishes a request with the real mosquitto_pub; returns its id. */
async function request(arm: string, body: Record<string, unknown> | string): Promise<string> {
  const id = typeof body === 'string' ? '' : ((body.id as string | undefined) ?? `r${++n}`);
  const payload = typeof body === 'string' ? body : JSON.stringify({ id, ...body });
  const { host, port } = broker();
  await run('mosquitto_pub', [
    '-h',
    host,
    '-p',
    String(port),
    '-q',
    '1',
    '-t',
    `arm/${arm}/request`,
    '-m',
    payload,
  ]);
  return id;
}

const mine = (id: string | null, arm?: string) =>
  feedback.filter((x) => x.f.id === id && (arm === undefined || x.arm === arm)).map((x) => x.f);

/** Waits for feedback of request `id` with `status` (and returns it). */
function waitFor(
  w: StatusWatcher,
  id: string | null,
  status: string,
  timeoutMs = 20_000,
  test = (_f: Feedback) => true,
) {
  return w.until(
    () => mine(id).find((f) => f.status === status && test(f)),
    timeoutMs,
    `${id} ${status}`,
  );
}

/** The latest state sample's pulse of servo `id`. */
const latest = (w: StatusWatcher, id: number) =>
  w.positions(id, Math.max(0, w.items.length - 20)).at(-1)?.[1];

describe('motion requests on the simulator', () => {
  test('each arm announces its profile, retained; track6 streams its 7 servos', async () => {
    await w6.until(
      () => (profiles.has(T6) && profiles.has(A5) ? true : undefined),
      10_000,
      'profiles',
    );
    const p6 = JSON.parse(profiles.get(T6)!) as {
      name: string;
      profile: { servos: unknown[]; ik: { kind: string } };
    };
    expect(p6.name).toBe('track6');
    expect(p6.profile.servos).toHaveLength(7);
    expect(p6.profile.ik.kind).toBe('numeric');
    expect(JSON.parse(profiles.get(A5)!)).toMatchObject({
      name: 'armtwin5',
      profile: { ik: { kind: 'analytic5' } },
    });
    const from = w6.items.length;
    const group = await w6.until(() => {
      for (let i = from; i < w6.items.length; i++) {
        const it = w6.items[i]!;
        if ('group' in it && it.group.frames[0]?.type === 'position') return it.group;
      }
      return undefined;
    });
    expect(group.frames.map((f) => ('id' in f ? f.id : -1))).toEqual([0, 1, 2, 3, 4, 5, 6]);
    expect(group.frames[0]).toMatchObject({ pwm: 500 }); // track6 home: the carriage at 0 mm
  });

  test('a request sent with mosquitto_pub is planned, executed, done, and the pose is reached', async () => {
    const id = await request(A5, { mode: 'joint', targets: ['ready'], execute: true, speed: 1 });
    const done = await waitFor(w5, id, 'done');
    expect(mine(id).map((f) => f.status)).toEqual(['planned', 'executing', 'done']);
    expect(mine(id)[1]).toMatchObject({ event: 'started', code: 0 });
    // ready: servo angles 0, −30, −60, −60, 0 → 1500, 1278, 1056, 1056, 1500 µs.
    expect(done.end).toMatchObject({ '000': 1500, '001': 1278, '002': 1056, '003': 1056 });
    await w5.until(() => (latest(w5, 2) === 1056 ? true : undefined), 5000, 'elbow at 1056');
    for (const [k, v] of Object.entries(done.end!)) expect(latest(w5, Number(k))).toBe(v);
  });

  test('plan only: answered planned, and nothing moves', async () => {
    const before = [0, 1, 2, 3].map((i) => latest(w5, i));
    const id = await request(A5, {
      mode: 'cartesian',
      targets: [{ x: 200, y: 0, z: 100, pitch: -60 }],
    });
    const planned = await waitFor(w5, id, 'planned');
    expect(planned.message).toMatch(/plan only/);
    await new Promise((r) => setTimeout(r, 600));
    expect(mine(id).map((f) => f.status)).toEqual(['planned']);
    expect([0, 1, 2, 3].map((i) => latest(w5, i))).toEqual(before);
  });

  test('unreachable targets: armtwin5 answers §4 codes 1, 2, 4, 6, 7, 8; track6 numeric codes 2 and 9', async () => {
    const cases: [string, Record<string, number>, number][] = [
      [A5, { x: -300, y: -200, z: -200 }, 1],
      [A5, { x: -300, y: -200, z: -50 }, 2],
      [A5, { x: -150, y: 0, z: 40, pitch: 0 }, 4],
      [A5, { x: -300, y: 0, z: 0, pitch: 0 }, 6],
      [A5, { x: -150, y: -200, z: 120, pitch: 45 }, 7],
      [A5, { x: -300, y: 0, z: 40, pitch: 0 }, 8],
      [T6, { x: 9000, y: 0, z: 0 }, 2],
      [T6, { x: 6559.85, y: 0, z: 1341.19 }, 9], // the carriage would have to be at 3.6 m (track: 3 m)
    ];
    for (const [arm, target, code] of cases) {
      const id = await request(arm, { mode: 'joint', targets: [target], execute: true });
      const f = await waitFor(arm === A5 ? w5 : w6, id, 'unreachable');
      expect({ code: f.code, target: f.target }, `${arm} ${JSON.stringify(target)}`).toEqual({
        code,
        target: 0,
      });
    }
    // A servo target beyond its limits: 21.
    const id = await request(A5, { mode: 'joint', targets: [{ servos: { '005': 1000 } }] });
    expect(await waitFor(w5, id, 'unreachable')).toMatchObject({
      code: 21,
      message: /servos\.005/,
    });
  });

  test('malformed requests are answered failed, naming the field, and the sim carries on', async () => {
    const bad: [Record<string, unknown> | string, string | null, string][] = [
      [{ id: 'bad-1', mode: 'joint', targets: [{ x: 'a', y: 0, z: 0 }] }, 'bad-1', 'targets[0].x'],
      [{ id: 'bad-2', mode: 'joint', targets: ['home'], colour: 'red' }, 'bad-2', 'colour'],
      [{ id: 'bad-3', mode: 'joint', targets: new Array(100).fill('home') }, 'bad-3', 'targets'],
      [{ id: 'bad-4', mode: 'joint', targets: ['nowhere'] }, 'bad-4', 'targets[0]'],
      [
        { id: 'bad-5', mode: 'joint', targets: [{ servos: { '009': 1500 } }] },
        'bad-5',
        'targets[0].servos.009',
      ],
      ['{"id": "bad-6", "mode": ', null, '(request)'],
    ];
    for (const [body, id, field] of bad) {
      await request(A5, body);
      const f = await waitFor(w5, id, 'failed', 10_000, (x) => x.field === field);
      expect(f.code).toBe(20);
      expect(f.message.startsWith(`${field}: `)).toBe(true);
    }
    const from = w5.items.length;
    await w5.send('$PNG:77!');
    await w5.frame((f) => f.type === 'ping' && f.seq === 77, from);
  });

  test('two arms on one broker each answer their own requests only', async () => {
    const id5 = await request(A5, { mode: 'joint', targets: ['home'] });
    const id6 = await request(T6, { mode: 'joint', targets: ['side'] });
    await waitFor(w5, id5, 'planned');
    await waitFor(w6, id6, 'planned');
    await new Promise((r) => setTimeout(r, 300));
    expect(feedback.filter((x) => x.f.id === id5).map((x) => x.arm)).toEqual([A5]);
    expect(feedback.filter((x) => x.f.id === id6).map((x) => x.arm)).toEqual([T6]);
  });

  test('track6 executes a Cartesian line with its numeric IK', async () => {
    const id = await request(T6, {
      mode: 'cartesian',
      targets: [{ x: 1500, y: 300, z: 1200, pitch: -90 }],
      execute: true,
      linearSpeed: 1000,
      speed: 1,
    });
    const done = await waitFor(w6, id, 'done', 60_000);
    for (const [k, v] of Object.entries(done.end!))
      expect(Math.abs(latest(w6, Number(k))! - v)).toBeLessThanOrEqual(1);
  });

  test('pose checking: a servo stalled mid-path pauses the arm, which re-plans from where it is', async () => {
    await request(A5, { id: 'to-home', mode: 'joint', targets: ['home'], execute: true, speed: 1 });
    await waitFor(w5, 'to-home', 'done');
    const id = await request(A5, {
      mode: 'joint',
      targets: [{ servos: { '000': 2300 } }],
      execute: true,
      speed: 0.2,
    });
    await waitFor(w5, id, 'executing', 10_000, (f) => f.event === 'started');
    await w5.until(() => ((latest(w5, 0) ?? 0) > 1600 ? true : undefined), 5000, 'base moving');
    await fb.publishAsync(`arm/${A5}/sim`, '{"fault":"stall","id":0}', { qos: 1 });
    const paused = await waitFor(w5, id, 'executing', 10_000, (f) => f.event === 'paused');
    expect(paused).toMatchObject({ servo: '000', code: 0 });
    await fb.publishAsync(`arm/${A5}/sim`, '{"fault":"clear"}', { qos: 1 });
    const replanned = await waitFor(w5, id, 'executing', 10_000, (f) => f.event === 'replanned');
    expect(replanned.replans).toBeGreaterThanOrEqual(1);
    await waitFor(w5, id, 'done', 20_000);
    await w5.until(() => (latest(w5, 0) === 2300 ? true : undefined), 5000, 'base at 2300');
  });

  test('#255PDST! ends an execution as stopped', async () => {
    const id = await request(A5, {
      mode: 'joint',
      targets: [{ servos: { '000': 700 } }],
      execute: true,
      speed: 0.1,
    });
    await waitFor(w5, id, 'executing', 10_000, (f) => f.event === 'started');
    await new Promise((r) => setTimeout(r, 300));
    await w5.send('#255PDST!');
    const stopped = await waitFor(w5, id, 'stopped');
    expect(stopped).toMatchObject({ code: 23, message: /emergency stop/ });
    const at = latest(w5, 0)!;
    await new Promise((r) => setTimeout(r, 400));
    expect(latest(w5, 0)).toBe(at);
    expect(at).toBeGreaterThan(700);
  });
});
