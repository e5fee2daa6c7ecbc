/**
 * Rough rate benchmark (not a test): real Mosquitto + influxd, the middleware as a child
 * process, a `mosquitto_pub -l` stream of 6-servo state groups at each given rate for
 * DURATION_S seconds. Reports points/s stored, loss, and the middleware's CPU (from
 * /proc/<pid>/stat, utime + stime over the run). Usage:
 *
 *   npx tsx apps/middleware/test/support/bench-rate.mts 1000 5000   # messages/s (×6 points)
 *   WRITE_MODE=sync npx tsx apps/middleware/test/support/bench-rate.mts 50
 */
import fs from 'node:fs';
import path from 'node:path';
import { freePort } from '../../../../tests/helpers/ports.ts';
import { startInflux, startMosquitto } from '../../../../tests/helpers/services.ts';
import {
  countPoints,
  spawnMiddleware,
  startPublisher,
  statePayloads,
  tempDir,
  waitForValue,
} from './harness.ts';

const DURATION_S = Number(process.env.DURATION_S ?? 15);
const rates = process.argv
  .slice(2)
  .map(Number)
  .filter((n) => n > 0);
const ticks = () => {
  const clk = 100; // USER_HZ
  return (pid: number) => {
    const f = fs.readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1]!.split(' ');
    return (Number(f[11]) + Number(f[12])) / clk; // utime + stime, seconds
  };
};
const cpu = ticks();

const broker = await startMosquitto({ extraConfig: ['max_queued_messages 1000000'] });
const influx = await startInflux();
let t0 = Date.UTC(2026, 5, 1);
try {
  for (const rate of rates.length ? rates : [1000]) {
    const dir = tempDir('mw-bench');
    const mw = await spawnMiddleware(
      {
        MQTT_URL: broker.url,
        MQTT_CLIENT_ID: `bench-${rate}`,
        INFLUX_URL: influx.url,
        INFLUX_BUCKET: influx.bucket,
        SPOOL_DIR: path.join(dir, 'spool'),
        WRITE_MODE: process.env.WRITE_MODE ?? 'batch',
        LOG_LEVEL: 'warn',
      },
      await freePort(),
      path.join(dir, 'mw.log'),
    );
    const inf = { url: influx.url, db: influx.db };
    const before = await countPoints(inf, 'servo', 'pwm');
    const n = rate * DURATION_S;
    const payloads = statePayloads(n, 6, t0);
    t0 += n + 1000;
    const pub = startPublisher(broker.port, 'arm/bench/status', 1);
    const cpu0 = cpu(mw.child.pid!);
    const w0 = Date.now();
    await pub.send(payloads, Math.max(1, Math.round(rate / 100)), rate < 100 ? 1000 / rate : 10);
    await pub.end();
    const sendS = (Date.now() - w0) / 1000;
    const cpuSend = cpu(mw.child.pid!) - cpu0;
    const want = before + 6 * n;
    const got = await waitForValue(() => countPoints(inf, 'servo', 'pwm'), want, 60_000, 500);
    const wallS = (Date.now() - w0) / 1000;
    const cpuS = cpu(mw.child.pid!) - cpu0;
    const m = await mw.metrics();
    console.log(
      JSON.stringify({
        mode: process.env.WRITE_MODE ?? 'batch',
        messagesPerS: rate,
        pointsPerS: Math.round((6 * n) / sendS),
        sentIn_s: +sendS.toFixed(1),
        storedAfter_s: +wallS.toFixed(1),
        expected: 6 * n,
        stored: got - before,
        lost: want - got,
        dropped: m['points_dropped_total'],
        batches: m['write_batches_total{result="ok"}'],
        cpuPercentWhileSending: +((100 * cpuSend) / sendS).toFixed(1),
        cpuPercentOverall: +((100 * cpuS) / wallS).toFixed(1),
        cpuSecondsPerMillionPoints: +((cpuS / (6 * n)) * 1e6).toFixed(1),
      }),
    );
    await mw.stop();
    fs.rmSync(dir, { recursive: true, force: true });
  }
} finally {
  await broker.dispose();
  await influx.dispose();
}
