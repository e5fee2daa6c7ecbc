/**
 * Several brokers at the edge gateway (docs/protocol.md § Several brokers): `armtwin gateway
 * --mqtt A,B` over a pty pair to the simulated controller, two real Mosquittos. Broker A is
 * SIGKILLed: the gateway moves to B (announces `online 1` there, logs the move) and control goes
 * through B to the line; A comes back: the gateway returns to it, and its last will says `0` on
 * B as it leaves. Only generous wait-for-condition timeouts, no timing assertion.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';
import { serialLine } from './serial-line.ts';

const ARM = 'gwbrokers';
const first = useMosquitto();
const second = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-pty-brokers-'));
const HOST_SIDE = path.join(dir, 'gateway');
const line = serialLine(
  HOST_SIDE,
  path.join(dir, 'arm'),
  (armSide) => ['sim', '--serial', armSide, '--rate', '20'],
  'simulated controller on the serial line',
);
let gateway: Child | undefined;
const watchers: StatusWatcher[] = [];

beforeAll(async () => {
  await line.start();
});

afterAll(async () => {
  await gateway?.stop('SIGKILL');
  await line.stop();
  await Promise.all(watchers.map((w) => w.close()));
  fs.rmSync(dir, { recursive: true, force: true });
});

const online = (w: StatusWatcher, v: string) => () =>
  w.retained.get(`arm/${ARM}/online`) === v ? true : undefined;

test('the gateway moves to the second broker when the first dies, carries control there, and comes back', async () => {
  const onA = await StatusWatcher.connect(first().url, ARM);
  const onB = await StatusWatcher.connect(second().url, ARM);
  watchers.push(onA, onB);
  gateway = armtwin([
    ...['gateway', '--serial', HOST_SIDE, '--baud', '115200'],
    ...['--mqtt', `${first().url},${second().url}`, '--arm', ARM],
  ]);
  await onA.until(online(onA, '1'), 20_000, 'online 1 on broker 1');
  expect(onB.retained.get(`arm/${ARM}/online`)).toBeUndefined();

  await first().kill();
  await onB.until(online(onB, '1'), 30_000, 'online 1 on broker 2');
  const logged = (re: RegExp) => () => (re.test(gateway!.output()) ? true : undefined);
  await onB.until(
    logged(/broker move: Broker 2 of 2: mqtt:\/\/127\.0\.0\.1:/),
    10_000,
    'the move logged',
  );
  // Control published on the second broker reaches the line; the status comes back there.
  // (resent every 2 s: the line may lose a frame while the gateway settles on broker 2).
  const from = onB.items.length;
  const at1650 = () => onB.positions(0, from).find(([, p]) => p === 1650);
  for (let tries = 0; !at1650() && tries < 10; tries++) {
    await onB.send('#000P1650T0100!');
    await onB.until(at1650, 2000, 'servo 000 at 1650').catch(() => undefined);
  }
  expect(at1650(), 'servo 000 moved to 1650 by a move sent on broker 2').toBeDefined();

  onA.retained.delete(`arm/${ARM}/online`);
  await first().start();
  await onA.until(online(onA, '1'), 60_000, 'online 1 on broker 1 again');
  await onB.until(online(onB, '0'), 30_000, "the gateway's last will on broker 2");
  await onA.until(logged(/broker move: Broker 1 of 2/), 10_000, 'the return logged');
}, 120_000);
