/**
 * Issue 20 item 2 on the real thing: `armtwin sim` on real Mosquitto, the middleware storing
 * its reports in a real InfluxDB 1.8. Ordinary scripted work (sweeps at top speed, random moves,
 * rests); the middleware's `/history/thermal-model` fits each servo's model from that stored
 * history; the same `ThermalWatch` the HUD runs, fed the arm's own status stream with those
 * parameters, raises no warning over the whole ordinary run, and warns of an injected stall at
 * least 10 s before the servo reports 60 °C.
 * The sim's heat runs `SCALE` times faster than the clock (`--thermal-time-scale`, with the
 * health rate raised as much), so the servos warm and cool in seconds, not minutes; the motion,
 * MQTT, the middleware and InfluxDB run in real time. The middleware fits on wall time (τ comes
 * out `SCALE` times shorter); the watch is then fed the reports on the sim's thermal time (their
 * times stretched by `SCALE`, the fitted τ and gain likewise), where its windows and the 10 s
 * lead mean what they mean on a real arm.
 * (Five minutes of ordinary work and the overheat fault run in sim time in
 * packages/sim/test/sim-thermal.test.ts.)
 */
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, describe, expect, test } from 'vitest';
import type { ThermalModelAnswer } from '@armtwin/api';
import {
  createReader,
  encodeMove,
  TEMP_WARNING_C,
  US_PER_DEG,
  type Frame,
} from '@armtwin/protocol';
import { ThermalWatch, type ThermalParams } from '@armtwin/thermal';
import { DEFAULT_SIM_MODEL_OPTIONS } from '../../packages/sim/src/options.ts';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { armtwin, type Child } from './sim-helpers.ts';

const ARM = 'thermal1';
/** Heat runs this many times faster than the clock in the sim. */
const SCALE = 4;
const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-thermal', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
let sim: Child | undefined;
let client: MqttClient | undefined;
afterAll(async () => {
  await client?.endAsync(true);
  await sim?.stop();
});

/** What the arm reported, as the HUD receives it: positions (µs) and health, by `$TIM`. */
interface Report {
  t: number;
  frames: Frame[];
}

const move = (id: number, deg: number, ms: number) =>
  encodeMove(id, Math.round(1500 + deg * US_PER_DEG), ms);

/**
 * A pose above the floor of the armtwin5 profile the sim loads: base and wrist roll anywhere in
 * ±60°, the shoulder in ±40° with the elbow bent back by as much (±20°), the wrist pitch in ±30°.
 */
const pose = (
  base: number,
  shoulder: number,
  bend: number,
  pitch: number,
  roll: number,
  ms: number,
) =>
  `{${move(0, base, ms)}${move(1, shoulder, ms)}${move(2, -shoulder + bend, ms)}${move(3, pitch, ms)}${move(4, roll, ms)}}`;

/** Ordinary work: a spell of sweeps at top speed, one of random moves, then rest. */
async function work(c: MqttClient, seconds: { sweep: number; random: number; rest: number }) {
  const send = (payload: string) => c.publishAsync(`arm/${ARM}/control`, payload, { qos: 1 });
  const sweepEnd = Date.now() + seconds.sweep * 1000;
  for (let side = 1; Date.now() < sweepEnd; side = -side) {
    await send(pose(side * 60, side * 40, 0, side * 30, side * 60, 100));
    await sleep(400);
  }
  let x = 12345;
  const rand = (lo: number, hi: number) =>
    lo + ((x = (x * 1664525 + 1013904223) >>> 0) / 2 ** 32) * (hi - lo);
  const randomEnd = Date.now() + seconds.random * 1000;
  while (Date.now() < randomEnd) {
    await send(
      pose(
        rand(-60, 60),
        rand(-40, 40),
        rand(-20, 20),
        rand(-30, 30),
        rand(-60, 60),
        Math.round(rand(300, 2300)),
      ),
    );
    await sleep(rand(1500, 3500));
  }
  await send(pose(0, 0, 0, 0, 0, 1500));
  await sleep(seconds.rest * 1000);
}

/** Reports on the sim's thermal time: times stretched by SCALE from `t0`. */
const onThermalTime = (reports: readonly Report[], t0: number): Report[] =>
  reports.map((r) => ({ t: t0 + (r.t - t0) * SCALE, frames: r.frames }));

/** Parameters fitted on wall time, on the sim's thermal time (motion looks SCALE× slower). */
const onThermalParams = (p: ThermalParams): ThermalParams => ({
  ...p,
  tauS: p.tauS * SCALE,
  gainCPerDegS: p.gainCPerDegS * SCALE,
  sagVPerDegS: p.sagVPerDegS * SCALE,
});

/** Feeds reports to a watch: returns its events and when each servo first reported ≥ 60 °C. */
function replay(watch: ThermalWatch, reports: readonly Report[], ids: readonly number[]) {
  const events: { t: number; id: number; event: string }[] = [];
  const crossed = new Map<number, number>();
  for (const r of reports)
    for (const f of r.frames) {
      if (f.type !== 'position' && f.type !== 'health') continue;
      const i = ids.indexOf(f.id);
      if (i < 0) continue;
      if (f.type === 'position') watch.position(i, f.pwm / US_PER_DEG);
      else {
        const e = watch.health(i, r.t, f.temp);
        if (e) events.push({ t: r.t, id: f.id, event: e });
        if (f.temp >= TEMP_WARNING_C && !crossed.has(f.id)) crossed.set(f.id, r.t);
      }
    }
  return { events, crossed };
}

describe('thermal model from the arm history (sim → Mosquitto → middleware → InfluxDB 1.8)', () => {
  test(
    'fitted from stored history, no warning in ordinary work; a stall warns ≥ 10 s before 60 °C',
    { timeout: 300_000 },
    async () => {
      const mw = await mws.spawn({ env: { FLUSH_INTERVAL_MS: '500' } });
      client = await mqtt.connectAsync(broker().url, { clientId: `thermal-${process.pid}` });
      const reports: Report[] = [];
      const reader = createReader({
        onFrame: (f) => {
          if (f.type === 'health' || f.type === 'position')
            reports.push({ t: f.time ?? Date.now(), frames: [f] });
        },
        onGroup: (g) => reports.push({ t: g.time ?? Date.now(), frames: g.frames }),
      });
      let online = false;
      client.on('message', (topic, payload) => {
        if (topic === `arm/${ARM}/status`) {
          reader.clearStamp();
          reader.feed(payload);
        } else if (topic === `arm/${ARM}/online`) online = String(payload) === '1';
      });
      await client.subscribeAsync([`arm/${ARM}/status`, `arm/${ARM}/online`], { qos: 1 });
      sim = armtwin([
        'sim',
        '--mqtt',
        broker().url,
        '--arm',
        ARM,
        '--rate',
        '50',
        '--thermal-time-scale',
        String(SCALE),
        '--health-rate',
        String(2 * SCALE),
      ]);
      for (let i = 0; i < 150 && !online; i++) await sleep(100);
      expect(online).toBe(true);

      // Ordinary work, then the model is fitted from what the middleware stored.
      const start = Date.now();
      // (On thermal time: 40 s of sweeps, 40 s of random moves, 40 s of rest.)
      await work(client, { sweep: 10, random: 10, rest: 10 });
      const fitStop = Date.now();
      await sleep(1500); // the middleware's last flush
      const url = `http://127.0.0.1:${mw.port}/api/history/thermal-model?arm=${ARM}&start=${start}&stop=${fitStop}`;
      const res = await fetch(url);
      expect(res.status).toBe(200);
      const answer = (await res.json()) as ThermalModelAnswer;
      expect(answer.servos.map((s) => s.id)).toEqual(['000', '001', '002', '003', '004', '005']);
      const o = DEFAULT_SIM_MODEL_OPTIONS;
      for (const s of answer.servos.slice(1, 3)) {
        const i = Number(s.id);
        const tau = o.thermalTauMs / 1000 / SCALE;
        const rest = o.ambientC + o.degPerAmp * o.holdAmps[i]!;
        const gain = (o.degPerAmp * o.moveAmps) / o.arm.servos[i]!.maxSpeedDegPerS;
        console.log(
          `servo ${s.id} fitted from InfluxDB: τ ${s.params.tauS.toFixed(1)} s (sim ${tau}), ` +
            `rest ${s.params.restC.toFixed(2)} °C (sim ${rest}), gain ${s.params.gainCPerDegS.toFixed(4)} (sim ${gain.toFixed(4)}), ` +
            `rmse ${s.rmseC?.toFixed(2)} °C, r² ${s.r2?.toFixed(3)}, ${s.intervals} intervals`,
        );
        expect(s.fitted && s.tauFitted).toBe(true);
        expect(Math.abs(s.params.tauS - tau) / tau).toBeLessThan(0.3);
        expect(Math.abs(s.params.restC - rest)).toBeLessThan(2);
        expect(Math.abs(s.params.gainCPerDegS - gain) / gain).toBeLessThan(0.3);
      }

      // More ordinary work (different moves), then a stall of the shoulder that pushes.
      await work(client, { sweep: 4, random: 6, rest: 6 });
      const normalEnd = reports.length;
      await client.publishAsync(`arm/${ARM}/sim`, JSON.stringify({ fault: 'stall', id: 1 }), {
        qos: 1,
      });
      await sleep(200);
      await client.publishAsync(`arm/${ARM}/control`, move(1, -30, 1000), { qos: 1 });
      const ids = o.arm.servos.map((s) => s.id);
      const hot = () =>
        reports.some((r) =>
          r.frames.some((f) => f.type === 'health' && f.id === 1 && f.temp >= 60),
        );
      for (let i = 0; i < 600 && !hot(); i++) await sleep(100);
      expect(hot()).toBe(true);

      // The watch the HUD runs, with the fitted parameters, over everything the arm reported.
      const watch = new ThermalWatch(answer.servos.map((s) => onThermalParams(s.params)));
      const stretched = onThermalTime(reports, reports[0]!.t);
      const normal = replay(watch, stretched.slice(0, normalEnd), ids);
      expect(normal.events).toEqual([]);
      const stalled = replay(watch, stretched.slice(normalEnd), ids);
      const raised = stalled.events.find((e) => e.id === 1 && e.event === 'raised');
      expect(raised).toBeDefined();
      const crossed = stalled.crossed.get(1)!;
      const lead = crossed - raised!.t;
      console.log(
        `stall (InfluxDB-fitted model, live stream, thermal time ×${SCALE}): warned ${lead / 1000} s ` +
          `(${lead / SCALE / 1000} s wall) before servo 001 reported 60 °C; ${normal.events.length} warnings in ` +
          `${((stretched[normalEnd - 1]!.t - stretched[0]!.t) / 1000).toFixed(0)} s of ordinary work`,
      );
      expect(lead).toBeGreaterThanOrEqual(10_000);
      expect(stalled.events.filter((e) => e.id !== 1)).toEqual([]);
    },
  );
});
