/**
 * No stale claim after a broker move (docs/protocol.md § Several brokers): the page's client
 * (its own factory, `brokerConnect`: @armtwin/link over real mqtt.js) on two real Mosquittos.
 * The broker the page is on hangs (SIGSTOP): the page's `take`, a move and an e-stop go out and
 * are never acknowledged. The broker dies (SIGKILL) and the page moves to the second, where the
 * arm listens. mqtt.js alone would send the three again there (its outgoing store, clean session
 * or not): the arm would be taken and moved seconds after the click. The arm gets the e-stop
 * only; a `take` made while the page is disconnected is refused, an e-stop then goes out.
 */
import mqtt from 'mqtt';
import { afterAll, expect, test } from 'vitest';
import { EMERGENCY_STOP, userTopic } from '@armtwin/protocol';
import { NOT_CONNECTED, type BrokerClient } from '@armtwin/link';
import { brokerConnect } from '../../apps/web/src/core/link/brokerConnect.ts';
import { connectOptions } from '../../apps/web/src/core/link/connectOptions.ts';
import { until } from '../helpers/until.ts';
import { useMosquitto } from '../helpers/use-services.ts';

const first = useMosquitto();
const second = useMosquitto();
const ARM = 'stale1';
let page: BrokerClient | undefined; // the page's factory's client, seen as what it is
let arm: mqtt.MqttClient | undefined;
afterAll(async () => {
  page?.end(true);
  await arm?.endAsync(true);
});

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

test('a take and a move unacknowledged when the broker dies are not sent to the next; the e-stop is', async () => {
  // The arm, on the second broker: what reaches it on its claim and control topics.
  arm = await mqtt.connectAsync(second().url, { clientId: 'arm' });
  const got: string[] = [];
  arm.on('message', (t, p) => got.push(`${t} ${p.toString()}`));
  await arm.subscribeAsync([`arm/${ARM}/claim/+`, `arm/${ARM}/control/+`], { qos: 0 });

  const opts = connectOptions('hud', { username: '', password: '' }, { reconnectPeriod: 200 });
  page = brokerConnect(`${first().url},${second().url}`, opts) as unknown as BrokerClient;
  const choice = () => page!.brokers.choice.index;
  await until(() => page!.connected && choice() === 0, 10_000, 'the page on broker 1');

  const claim = userTopic(ARM, 'claim', 'alice');
  const control = userTopic(ARM, 'control', 'alice');
  const results: Record<string, string> = {};
  const send = (topic: string, payload: string, name: string) =>
    page!.publish(topic, payload, { qos: 1 }, (err) => (results[name] = err?.message ?? 'ok'));

  // The broker hangs: what the page sends now is written to the socket, never acknowledged.
  process.kill(first().pid!, 'SIGSTOP');
  send(claim, 'take', 'take');
  send(control, '#000P1600T0500!', 'move');
  send(control, EMERGENCY_STOP, 'stop');
  await sleep(200);
  expect(results).toEqual({}); // none acknowledged
  // Once the connection is closed, before the next: a take is refused at once, an e-stop waits
  // for the next connection.
  page!.once('close', () => {
    send(claim, 'take', 'offline take');
    send(control, EMERGENCY_STOP, 'offline stop');
  });
  await first().kill(); // the broker dies: the page's connection closes, it moves

  await until(() => page!.connected && choice() === 1, 15_000, 'the page on broker 2');
  await until(
    () => got.filter((m) => m.endsWith(EMERGENCY_STOP)).length === 2 && !!results['offline stop'],
    10_000,
    `both e-stops at the arm and acknowledged (got ${JSON.stringify(got)})`,
  );
  // mqtt.js re-sends its store in order, each message after the previous one's PUBACK: a take
  // or a move re-sent would have reached the arm before the first e-stop.
  expect(got).toEqual([`${control} ${EMERGENCY_STOP}`, `${control} ${EMERGENCY_STOP}`]);
  expect(results).toEqual({
    take: 'Message removed',
    move: 'Message removed',
    stop: 'ok',
    'offline take': NOT_CONNECTED,
    'offline stop': 'ok',
  });
});
