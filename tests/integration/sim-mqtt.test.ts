/**
 * `armtwin sim` through a real Mosquitto: the commands of PROTOCOL.md §1 answered as the
 * firmware would, motion timed by the sim's own `$TIM` stamps, presence, fault injection.
 */
import { execFileSync } from 'node:child_process';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { solveIk } from '@armtwin/ik';
import { parseSummary, type ArmSummary } from '@armtwin/protocol';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'simtest';
const RATE = 100; // Hz: one state period is 10 ms
const PERIOD = 1000 / RATE;

const broker = useMosquitto();
let sim: Child;
let w: StatusWatcher;
let seq = 1000;

beforeAll(async () => {
  w = await StatusWatcher.connect(broker().url, ARM);
  sim = armtwin(['sim', '--mqtt', broker().url, '--arm', ARM, '--rate', String(RATE)]);
  await w.online();
});

afterAll(async () => {
  await sim?.stop('SIGKILL');
  await w?.close();
});

/** Sends frames after a ping; resolves with the sim's receive time (the ping echo's `$TIM`). */
async function sendStamped(frames: string) {
  const n = ++seq;
  const from = w.items.length;
  await w.send(`$PNG:${n}!${frames}`);
  const echo = await w.frame((f) => f.type === 'ping' && f.seq === n, from);
  return { t: echo.time, from };
}

describe('armtwin sim over Mosquitto', () => {
  test('streams stamped state groups at the rate and health groups', async () => {
    const from = w.items.length;
    await w.until(
      () => (w.positions(0, from).length >= 50 ? true : undefined),
      10_000,
      '50 samples',
    );
    const stamps = w.positions(0, from).map(([t]) => t);
    expect(new Set(stamps).size).toBe(stamps.length);
    for (let i = 1; i < stamps.length; i++) expect(stamps[i]! - stamps[i - 1]!).toBeGreaterThan(0);
    const health = await w.until(() => w.health(1), 5000, 'health');
    expect(health.mv).toBeGreaterThan(6500);
  });

  test('$PNG is echoed', async () => {
    const from = w.items.length;
    await w.send('$PNG:4294967295!');
    expect((await w.frame((f) => f.type === 'ping' && f.seq === 4294967295, from)).frame).toEqual({
      type: 'ping',
      seq: 4294967295,
      time: expect.any(Number),
    });
  });

  test('$KMS answers the IK status code for reachable targets and each kind of unreachable one', async () => {
    // Code 5 (no triangle at the elbow) cannot happen on this arm: with L1 = 105 and L2 = 98,
    // |cos β| > 1 below the reach needs d < 7 mm, where |cos A| > 1 already gives code 3.
    const targets: [number, number, number, number?][] = [
      [150, 50, 120],
      [-150, -200, 50],
      [0, 0, 453, 90],
      [-300, -200, -200], // 1
      [-300, -200, -50], // 2
      [0, 0, -50], // 3
      [-150, 0, 40, 0], // 4
      [-300, 0, 0, 0], // 6
      [-150, -200, 120, 45], // 7
      [-300, 0, 40, 0], // 8 (base yaw limit)
    ];
    const seen = new Set<number>();
    for (const [x, y, z, a] of targets) {
      const expected = solveIk(x, y, z, a).code;
      seen.add(expected);
      const from = w.items.length;
      await w.send(`$KMS:${x},${y},${z}${a === undefined ? '' : `,${a}`},0300!`);
      const got = await w.frame((f) => f.type === 'kmsResult', from);
      expect(got.frame, `$KMS:${x},${y},${z},${a}`).toMatchObject({
        type: 'kmsResult',
        code: expected,
      });
    }
    expect([...seen].sort()).toEqual([0, 1, 2, 3, 4, 6, 7, 8]);
    // Reachable by §4, but with the hand under the floor: refused with §4's floor code, 1.
    expect(solveIk(-150, -200, -50).code).toBe(0);
    const from = w.items.length;
    await w.send('$KMS:-150,-200,-50,0300!');
    expect((await w.frame((f) => f.type === 'kmsResult', from)).frame).toMatchObject({ code: 1 });
  });

  test('nothing moves when $KMS is refused; the pose is reached when accepted', async () => {
    const target = solveIk(150, 50, 120);
    const { t } = await sendStamped('$KMS:150,50,120,0500!');
    await w.until(
      () => (w.positions(3).at(-1)?.[1] === target.pwm[3] ? true : undefined),
      5000,
      'the IK pose',
    );
    const before = w.items.length;
    await sendStamped('$KMS:-300,-200,-50,0500!');
    await new Promise((r) => setTimeout(r, 300));
    for (const j of [0, 1, 2, 3]) {
      expect(new Set(w.positions(j, before).map(([, p]) => p))).toEqual(new Set([target.pwm[j]]));
    }
    expect(t).toBeGreaterThan(0);
  });

  test('a move reaches its target within ±10 % of the commanded time ($TIM-measured)', async () => {
    await sendStamped('#000P1500T0000!');
    await w.until(
      () => (w.positions(0).at(-1)?.[1] === 1500 ? true : undefined),
      5000,
      'servo 000 at 1500',
    );
    const { t, from } = await sendStamped('#000P2000T1000!');
    const arrival = await w.until(
      () => w.positions(0, from).find(([, p]) => p === 2000),
      5000,
      'arrival',
    );
    expect(arrival[0] - t).toBeGreaterThanOrEqual(900);
    expect(arrival[0] - t).toBeLessThanOrEqual(1100);
    const halfway = w.positions(0, from).find(([time]) => time >= t + 500)!;
    expect(Math.abs(halfway[1] - 1750)).toBeLessThan(40);
  });

  test('#255PDST! stops every servo within one state period', async () => {
    // Forearm pointing up at both ends (a pose with the hand under the floor is refused).
    await sendStamped('{#001P1000T0000!#002P2000T0000!}');
    await w.until(
      () => (w.positions(2).at(-1)?.[1] === 2000 ? true : undefined),
      5000,
      'start pose',
    );
    const { t: start } = await sendStamped('{#001P2000T2000!#002P1000T2000!}');
    await w.until(() => w.positions(1).find(([time]) => time > start + 300), 5000, 'motion');
    const { t: stopAt, from } = await sendStamped('#255PDST!');
    await new Promise((r) => setTimeout(r, 400));
    for (const id of [1, 2]) {
      const after = w.positions(id, from).filter(([time]) => time >= stopAt + PERIOD);
      expect(after.length).toBeGreaterThan(10);
      expect(new Set(after.map(([, p]) => p)).size).toBe(1);
      expect(after[0]![1]).toBeGreaterThan(1000);
      expect(after[0]![1]).toBeLessThan(2000);
    }
  });

  test('bad frames get $ERR, out-of-limit moves and bad groups move nothing, and the sim still answers', async () => {
    const from = w.items.length;
    await w.send('#00XP1500T1000!');
    const err = await w.frame((f) => f.type === 'controllerError', from);
    expect(err.frame).toMatchObject({
      type: 'controllerError',
      text: expect.stringMatching(/malformed|junk/),
    });
    const from2 = w.items.length;
    await w.send('#005P1000T0100!{#000P1600T0100!#005P1000T0100!}');
    const limit = await w.frame(
      (f) => f.type === 'controllerError' && f.text.startsWith('limit'),
      from2,
    );
    expect(limit.frame).toMatchObject({ text: 'limit 005 P1000 outside 1500-2167' });
    await w.frame(
      (f) => f.type === 'controllerError' && f.text.startsWith('group rejected'),
      from2,
    );
    const { from: after } = await sendStamped('');
    await new Promise((r) => setTimeout(r, 200));
    expect(w.positions(0, after).every(([, p]) => p !== 1600)).toBe(true);
    expect(w.positions(5, after).every(([, p]) => p === 1500)).toBe(true);
  });

  test('a payload that ends in "!" but is no frame gets its $ERR at once, before anything else is sent', async () => {
    const from = w.items.length;
    // An outside client, as an operator would type it: nothing follows it on the topic.
    execFileSync('mosquitto_pub', [
      ...['-h', '127.0.0.1', '-p', String(broker().port)],
      ...['-t', `arm/${ARM}/control`, '-q', '1', '-m', 'hello world!'],
    ]);
    const { frame } = await w.frame((f) => f.type === 'controllerError', from);
    expect(frame).toMatchObject({ type: 'controllerError', text: 'junk hello world' });
  });

  test('rate limit: of 300 moves at once the first 100 (the burst) run, the rest are dropped with one $ERR:rate limit!', async () => {
    const from = w.items.length;
    const moves = Array.from({ length: 300 }, (_, i) => `#000P${1000 + i}T0000!`).join('');
    await w.send(moves);
    await w.frame((f) => f.type === 'controllerError' && f.text === 'rate limit', from);
    await w.until(
      () => (w.positions(0, from).at(-1)?.[1] === 1099 ? true : undefined),
      5000,
      'the 100th move (P1099)',
    );
    await new Promise((r) => setTimeout(r, 300));
    const seen = w.positions(0, from).map(([, p]) => p);
    expect(seen.slice(seen.indexOf(1099))).toEqual(seen.slice(seen.indexOf(1099)).map(() => 1099));
    // Had the other 200 run, the arm would have settled on P1299, never P1099.
    const errors = w.items
      .slice(from)
      .filter((it) => 'frame' in it && it.frame.type === 'controllerError');
    expect(errors).toHaveLength(1);
  });

  test('rate limit: a stop behind a flood of moves is never dropped, and overrides them all', async () => {
    await new Promise((r) => setTimeout(r, 2500)); // the bucket refills
    const before = w.positions(0).at(-1)![1];
    const { from } = await sendStamped('');
    const moves = Array.from({ length: 300 }, (_, i) => `#000P${2000 + i}T0500!`).join('');
    await w.send(`${moves}#255PDST!`);
    await w.frame((f) => f.type === 'controllerError' && f.text === 'rate limit', from);
    await new Promise((r) => setTimeout(r, 800));
    expect(new Set(w.positions(0, from).map(([, p]) => p))).toEqual(new Set([before]));
    await new Promise((r) => setTimeout(r, 2500)); // leave a full bucket for the next test
  });

  test('fault injection at runtime: overheat passes 60 °C; stall freezes a servo; clear restores', async () => {
    await w.client.publishAsync(
      `arm/${ARM}/sim`,
      '[{"fault":"overheat","id":2,"celsius":95},{"fault":"stall","id":4}]',
    );
    await w.until(
      () => (w.retained.get(`arm/${ARM}/sim/faults`)?.includes('"stalled":[4]') ? true : undefined),
      5000,
      'faults',
    );
    const { from } = await sendStamped('#004P1800T0200!');
    await w.until(() => ((w.health(2)?.temp ?? 0) >= 60 ? true : undefined), 15_000, '60 °C');
    expect(w.positions(4, from).every(([, p]) => p === 1500)).toBe(true);
    await w.client.publishAsync(`arm/${ARM}/sim`, '{"fault":"clear"}');
    await w.until(
      () => (w.positions(4).at(-1)?.[1] === 1800 ? true : undefined),
      5000,
      'resume after clear',
    );
    await w.client.publishAsync(`arm/${ARM}/sim`, '{"fault":"nonsense"}');
    await w.until(
      () => (w.retained.get(`arm/${ARM}/sim/faults`)?.includes('"error"') ? true : undefined),
      5000,
      'fault error',
    );
  });

  test('its summary on arm/{id}/summary (docs/protocol.md § Fleets): pose, state, an overheat', async () => {
    await w.client.subscribeAsync(`arm/${ARM}/summary`, { qos: 0 });
    const summary = (ok: (s: ArmSummary) => boolean) => () => {
      const r = parseSummary(w.retained.get(`arm/${ARM}/summary`) ?? '');
      return r.ok && ok(r.summary) ? r.summary : undefined;
    };
    const first = await w.until(
      summary(() => true),
      5000,
      'a summary',
    );
    expect(first.joints.map((j) => j.id)).toEqual([0, 1, 2, 3, 4, 5]);
    expect(first.holder).toBeNull();
    await w.client.publishAsync(`arm/${ARM}/sim`, '{"fault":"overheat","id":1,"celsius":150}');
    // (The stall above left servo 004's supply low: the arm may be critical already.)
    const hot = await w.until(
      summary((s) => Number(/servo 001: (\d+) °C/.exec(s.alarm)?.[1] ?? 0) > 75),
      30_000,
      'servo 001 hot in the summary',
    );
    expect(hot.health).toBe('critical');
    await w.client.publishAsync(`arm/${ARM}/sim`, '{"fault":"clear"}');
    await sendStamped('#000P1700T0600!');
    await w.until(
      summary((s) => s.state === 'moving'),
      5000,
      'moving',
    );
    const still = await w.until(
      summary((s) => s.state === 'still'),
      5000,
      'still again',
    );
    expect(still.joints[0]!.deg).toBeGreaterThan(10);
  });

  test('on SIGTERM it publishes online 0 (retained), clears its summary and exits 0', async () => {
    const code = await sim.stop('SIGTERM');
    expect(code).toBe(0);
    await w.until(
      () => (w.retained.get(`arm/${ARM}/online`) === '0' ? true : undefined),
      5000,
      'online 0',
    );
    expect(w.retained.get(`arm/${ARM}/summary`)).toBe('');
  });
});
