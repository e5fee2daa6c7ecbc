/**
 * Hostile input, against the real middleware, Mosquitto and influxd: arm ids (topics)
 * and frame texts with quotes, commas, spaces, newlines, backslashes and `=` never reach line
 * protocol or Flux: nothing is stored under a forged series, bad topics are dropped and
 * counted, oversize messages are refused and counted, the history API refuses a hostile arm.
 */
import fs from 'node:fs';
import mqtt from 'mqtt';
import { expect, test } from 'vitest';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { select } from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-hostile', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

const T = Date.UTC(2026, 4, 1);
const HOSTILE_ARMS = [
  'a"b',
  "a'b",
  'a,b',
  'a b',
  'a\nb',
  'a\\b',
  'a=b',
  'arm1,arm=evil',
  'x y=1 z',
  'evil") |> drop() x',
  'ARM1',
  'a'.repeat(33),
  '',
];
const HOSTILE_FRAMES = [
  '#000P1500!"',
  '$ERR:x",arm=evil y=1 1!',
  '#000P15 00!',
  '#000P1500\n!',
  '#000P1500\\!',
  '{#000P1500!#001P=1!}',
  '#000P1500,arm=evil!',
  '$KMS:1,2,3\n,4,500!',
  '#002T045V7400 x=1!',
];

test(
  'hostile arm ids and frame texts: nothing stored under a forged series, all counted',
  { timeout: 90_000 },
  async () => {
    const mw = await mws.spawn({
      env: {
        FLUSH_INTERVAL_MS: '200',
        MAX_PAYLOAD_BYTES: '4096',
      },
    });
    // Mosquitto itself refuses some topics (a control character is a malformed packet: it
    // closes the connection); the rest reach the middleware.
    const refusedByBroker: string[] = [];
    for (const arm of HOSTILE_ARMS) {
      const c = await mqtt.connectAsync(broker().url, { reconnectPeriod: 0 });
      c.on('error', () => {});
      const closed = new Promise<'closed'>((r) => c.once('close', () => r('closed')));
      const r = await Promise.race([
        c.publishAsync(`arm/${arm}/status`, `$TIM:${T}!{#000P1500!}`, { qos: 1 }).then(() => 'ok'),
        closed,
      ]);
      if (r === 'closed') refusedByBroker.push(arm);
      c.end(true);
    }
    expect(refusedByBroker).toEqual(['a\nb']);
    const pub = await mqtt.connectAsync(broker().url);
    for (const [i, frame] of HOSTILE_FRAMES.entries())
      await pub.publishAsync('arm/hostile1/status', `$TIM:${T + 10 + i}!${frame}`, { qos: 1 });
    await pub.publishAsync('arm/hostile1/status', `$TIM:${T + 100}!#003P1234!`, { qos: 1 }); // a good one
    await pub.publishAsync('arm/hostile1/status', '#001P1600!'.repeat(500), { qos: 1 }); // 5000 B
    await pub.endAsync();

    let m = await mw.metrics();
    for (let i = 0; i < 40 && (m['frames_rejected_total{reason="oversize"}'] ?? 0) < 1; i++) {
      await sleep(250);
      m = await mw.metrics();
    }
    expect(m['frames_rejected_total{reason="bad-topic"}']).toBe(
      HOSTILE_ARMS.length - refusedByBroker.length,
    );
    expect(m['frames_rejected_total{reason="oversize"}']).toBe(1);
    expect(m['points_dropped_total']).toBe(0);

    const db = { url: influx().url, db: influx().db };
    let rows: unknown[][] = [];
    for (let i = 0; i < 40 && rows.length < 1; i++) {
      rows = await select(db, `SELECT pwm FROM servo WHERE arm = 'hostile1' AND id = '003'`);
      if (rows.length < 1) await sleep(250);
    }
    await sleep(500);
    expect(rows.map((r) => r[1])).toEqual([1234]);
    const series = (await select(db, 'SHOW SERIES')).map((r) => String(r[0])).sort();
    // Only the well-formed frames of hostile1 made points: the group's valid #000, #000P1500 of
    // the frames whose junk came after the `!`, and the good #003. No other arm, no other tag.
    expect(
      series.every((s) => /^servo,arm=hostile1,id=00[0-3]$/.test(s)),
      series.join('\n'),
    ).toBe(true);
    const arms = (await select(db, 'SHOW TAG VALUES WITH KEY = "arm"')).map((r) => r[1]);
    expect(arms).toEqual(['hostile1']);
    const measurements = (await select(db, 'SHOW MEASUREMENTS')).map((r) => r[0]);
    expect(measurements).toEqual(['servo']);
    expect(await select(db, `SELECT count(pwm) FROM servo WHERE id = '001'`)).toEqual([]); // the oversize one

    // The history API validates the arm before any Flux is built.
    for (const arm of ['hostile1") |> drop() //', 'a,b', 'a b', 'a\nb']) {
      const res = await fetch(
        `http://127.0.0.1:${mw.port}/history/series?arm=${encodeURIComponent(arm)}&field=pwm&start=-1h`,
      );
      expect(res.status).toBe(400);
      expect(((await res.json()) as { parameter: string }).parameter).toBe('arm');
    }
    expect(fs.readFileSync(mws.log(), 'utf8')).toContain('bad-topic');
  },
);
