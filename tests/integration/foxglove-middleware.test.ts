/**
 * The live Foxglove server in the middleware, for deployments without `armtwin up`
 * (`FOXGLOVE_PORT`, docs/foxglove.md): real Mosquitto running the configuration generated from
 * the sample users file (roles enforced by its ACL), a simulated arm logged in as its device, and
 * the real middleware process watching with its own `middleware` account. Foxglove's npm client
 * (`@foxglove/ws-protocol`, foxglove.websocket.v1) logs in as a viewer: it sees the arm's
 * channels and its joints as the arm reports them, and its publish is refused; as an operator:
 * its take goes to the broker under its own name, so the arm's controller grants it, its jog
 * moves the arm, and closing the client gives the arm back.
 */
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import type { ServiceProcess } from '../helpers/process.ts';
import { startDeployedMosquitto } from '../helpers/mosquitto.ts';
import { freePort } from '../helpers/services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { NpmFoxglove } from '../helpers/foxglove.ts';
import { password, USERS_FILE } from './auth-cases.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'arm1';
const { profile } = readRobotFolder('armtwin5');
let svc: ServiceProcess;
let mqttUrl = '';
let sim: Child | undefined;
let watcher: StatusWatcher;
let url = '';
const clients: NpmFoxglove[] = [];
const mws = useMiddlewares('foxglove-mw', () => ({ mqttUrl }));

beforeAll(async () => {
  svc = await startDeployedMosquitto('mosquitto-foxglove', USERS_FILE);
  mqttUrl = `mqtt://127.0.0.1:${svc.spec.ports[0]!}`;
  sim = armtwin([
    'sim',
    '--mqtt',
    mqttUrl,
    '--arm',
    ARM,
    '--rate',
    '50',
    '--username',
    ARM,
    '--password',
    password(ARM),
  ]);
  watcher = await StatusWatcher.connect(mqttUrl, ARM, {
    username: 'viewer',
    password: password('viewer'),
  });
  await watcher.client.subscribeAsync(`arm/${ARM}/holder`, { qos: 1 });
  await watcher.online();
  const port = await freePort();
  await mws.spawn({
    env: {
      MQTT_USERNAME: 'middleware',
      MQTT_PASSWORD: password('middleware'),
      ARMTWIN_USERS: USERS_FILE,
      FOXGLOVE_PORT: String(port),
    },
  });
  url = `ws://127.0.0.1:${port}`;
}, 60_000);

afterAll(async () => {
  for (const c of clients) c.close();
  await watcher?.client.endAsync();
  await sim?.stop();
  await svc?.dispose({ keepLogs: false });
});

const connect = async (user: string) => {
  const c = await NpmFoxglove.connect(url, user);
  clients.push(c);
  return c;
};

const holder = () =>
  (JSON.parse(watcher.retained.get(`arm/${ARM}/holder`) ?? '{}') as { user?: string }).user;

type Joints = { name: string; position: number }[];

describe('the middleware’s Foxglove server (FOXGLOVE_PORT) on Mosquitto with roles', () => {
  test('no log-in is refused; a viewer sees the arm’s joints and its publish is refused', async () => {
    await expect(NpmFoxglove.connect(url)).rejects.toThrow(/401/);
    const viewer = await connect('viewer');
    const states = await viewer.subscribe(`/${ARM}/joint_states`);
    const [m] = await viewer.until(() => states.length > 0 && states, 'joint states');
    const joints = m!.body.joints as Joints;
    expect(joints.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    expect(joints.every((j) => Number.isFinite(j.position))).toBe(true);

    const before = watcher.items.length;
    viewer.publish(`/${ARM}/jog`, { joint: 'base_yaw', delta: 0.5, ms: 500 });
    const refusal = await viewer.until(
      () => viewer.statuses.find((s) => /refused/.test(s.message)),
      'a refusal',
    );
    expect(refusal.message).toMatch(/viewer is a viewer/);
    expect((await viewer.call(`/${ARM}/take`)).ok).toBe(false);
    await new Promise((r) => setTimeout(r, 800));
    expect(new Set(watcher.positions(0, before).map(([, p]) => p)).size).toBe(1);
  });

  test('an operator’s take is granted under its own name, its jog moves the arm, closing releases it', async () => {
    const op = await connect('operator');
    const states = await op.subscribe(`/${ARM}/joint_states`);
    const targets = await op.subscribe(`/${ARM}/targets`);
    expect((await op.call(`/${ARM}/take`)).ok).toBe(true);
    await watcher.until(() => holder() === 'operator' || undefined, 10_000, 'operator holds arm1');
    const start = watcher.positions(1).at(-1)![1];
    const from = watcher.items.length;
    op.publish(`/${ARM}/jog`, { joint: 'shoulder', delta: 0.4, ms: 1500 });
    await watcher.until(
      () => watcher.positions(1, from).some(([, p]) => Math.abs(p - start) > 100) || undefined,
      10_000,
      'the shoulder moving',
    );
    // the client sees it move, and what was sent, by whom
    await op.until(
      () => new Set(states.map((s) => (s.body.joints as Joints)[1]!.position)).size > 3,
      'the shoulder moving in Foxglove',
    );
    await op.until(() => targets.some((t) => t.body.by === 'operator'), "the operator's target");
    // closing Foxglove gives the arm back: the server heard the arm's holder record with the
    // middleware's account, so it knows its user holds the arm, and releases it as that user
    op.close();
    await watcher.until(() => holder() !== 'operator' || undefined, 10_000, 'arm1 released');
  });
});
