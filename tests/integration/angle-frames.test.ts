/**
 * Angle frames (PROTOCOL §8) end to end on the real Mosquitto and influxd: `armtwin sim
 * --report angle` streams `#IIIA±ddd.dd!`, the middleware stores them as `angle` points with no
 * `pwm`; and a bus servo with ±360° of travel round-trips +350.00° without loss: moved by the
 * sim, reported as `#004A+350.00!`, stored as 350 (report and command), and held by the HUD's
 * store as 350.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import type { Frame } from '@armtwin/protocol';
import { MODELS_DIR } from '@armtwin/sim';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { select, waitForValue } from '../../apps/middleware/test/support/harness.ts';
import { ArmStore } from '../../apps/web/src/core/store/ArmStore.ts';
import { robotSpec } from '../../apps/web/src/core/robots/robotSpec.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('angle-frames', () => ({ mqttUrl: broker().url, influx: influx() }));
const sims: Child[] = [];
const watchers: StatusWatcher[] = [];

beforeAll(async () => {
  await mws.spawn({ env: { FLUSH_INTERVAL_MS: '200' } });
});

afterAll(async () => {
  await Promise.all(sims.map((s) => s.stop('SIGKILL')));
  await Promise.all(watchers.map((w) => w.close()));
});

async function startSim(arm: string, args: string[]): Promise<StatusWatcher> {
  const w = await StatusWatcher.connect(broker().url, arm);
  watchers.push(w);
  sims.push(armtwin(['sim', '--mqtt', broker().url, '--arm', arm, '--rate', '20', ...args]));
  await w.until(
    () => (w.retained.get(`arm/${arm}/online`) === '1' ? true : undefined),
    20_000,
    'online 1',
  );
  return w;
}

const inf = () => ({ url: influx().url, db: influx().db });
const count = async (q: string) => Number((await select(inf(), q).catch(() => []))[0]?.[1] ?? 0);

/** The latest state group's frame for servo `id`, or undefined. */
function latest(w: StatusWatcher, id: number): Frame | undefined {
  for (let i = w.items.length - 1; i >= 0; i--) {
    const it = w.items[i]!;
    if ('group' in it && it.group.frames.length >= 6)
      return it.group.frames.find((f) => 'id' in f && f.id === id);
  }
  return undefined;
}

describe('angle frames through the sim, the broker and the middleware', () => {
  test('armtwin sim --report angle streams angle frames, stored as angle points without pwm', async () => {
    const w = await startSim('angles1', ['--report', 'angle']);
    await w.send('#001A+030.00T0200!');
    const f = await w.until(
      () => {
        const g = latest(w, 1);
        return g?.type === 'angle' && g.deg === 30 ? g : undefined;
      },
      10_000,
      'servo 001 at +30.00°',
    );
    expect(f).toMatchObject({ type: 'angle', id: 1, deg: 30 });
    const where = `FROM "servo" WHERE "arm" = 'angles1'`;
    const at30 = `SELECT count("angle") ${where} AND "id" = '001' AND "angle" = 30`;
    expect(await waitForValue(() => count(at30).then((n) => n >= 1), true, 20_000)).toBe(true);
    expect(await count(`SELECT count("angle") ${where}`)).toBeGreaterThan(6);
    expect(await count(`SELECT count("pwm") ${where}`)).toBe(0);
    const cmd = await select(
      inf(),
      `SELECT "angle", "ms", "pwm" FROM "command" WHERE "arm" = 'angles1'`,
    );
    expect(cmd.map((r) => r.slice(1))).toEqual([[30, 200, null]]);
  });

  test('a ±360° bus servo round-trips +350.00° without loss: sim, wire, storage, HUD store', async () => {
    // armtwin5 with its wrist roll (004) a bus servo: angle frames, ±360° of travel
    const models = fs.mkdtempSync(path.join(mws.dir(), 'models-'));
    const raw = JSON.parse(
      fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
    ) as {
      name: string;
      servos: Record<string, unknown>[];
    };
    raw.name = 'bus5';
    raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
    fs.mkdirSync(path.join(models, 'bus5'));
    fs.writeFileSync(path.join(models, 'bus5', 'profile.json'), JSON.stringify(raw));
    const parsed = parseProfile(raw);
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const store = new ArmStore({ arm: robotSpec(parsed.profile).storeArm });
    const payloads: string[] = [];

    const w = await startSim('bus1', ['--profile', 'bus5', '--models', models]);
    w.client.on('message', (topic, payload) => {
      if (topic === 'arm/bus1/status') payloads.push(payload.toString());
    });
    const before = w.items.length;
    await w.send('#004A+361.00T0100!'); // beyond its limit: refused
    expect((await w.frame((f) => f.type === 'controllerError', before)).frame).toMatchObject({
      text: 'limit 004 A361 outside -360..360',
    });
    await w.send('#004A+350.00T0500!');
    await w.until(
      () => {
        const g = latest(w, 4);
        return g?.type === 'angle' && g.deg === 350 ? true : undefined;
      },
      10_000,
      'servo 004 at +350.00°',
    );
    expect(payloads.some((p) => p.includes('#004A+350.00!'))).toBe(true);
    expect(payloads.some((p) => p.includes('#000P1500!'))).toBe(true); // the pulse servos beside it

    const stored = `SELECT count("angle") FROM "servo" WHERE "arm" = 'bus1' AND "id" = '004' AND "angle" = 350`;
    expect(await waitForValue(() => count(stored).then((n) => n >= 1), true, 20_000)).toBe(true);
    expect(
      await count(`SELECT count("pwm") FROM "servo" WHERE "arm" = 'bus1' AND "id" = '004'`),
    ).toBe(0);
    const cmd = await select(
      inf(),
      `SELECT "angle", "ms", "pwm" FROM "command" WHERE "arm" = 'bus1'`,
    );
    // what was commanded, refused or not (storage records commands as sent, as for pulses)
    expect(cmd.map((r) => r.slice(1))).toEqual([
      [361, 100, null],
      [350, 500, null],
    ]);

    payloads.forEach((p, i) => store.ingest(p, i));
    store.sample(payloads.length + 1000);
    expect(store.angle[4]).toBe(350);
    expect(store.rendered[4]).toBe(350);
  });
});
