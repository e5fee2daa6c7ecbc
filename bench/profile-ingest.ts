/**
 * The middleware's CPU profile under the ingest load (issue 34 item 1): a throwaway Mosquitto and
 * influxd, the middleware under `node --cpu-prof`, the bench's publisher at R six-servo groups/s
 * for D s (QoS 0, as ./ingest.ts), every point awaited in InfluxDB, then SIGTERM (the profile is
 * written at exit) and the functions by self time, as shares of the samples outside `(idle)`.
 * Shares, not rates: on a loaded machine the rates move, the shares much less.
 *
 *   npx tsx bench/profile-ingest.ts [rate=20000] [seconds=10] [top=25] [group|frame] [prof|noprof] [NAME=value…]
 *
 * `frame`: one `$TIM`-stamped frame per message instead of a 6-servo group (the publisher's
 * other shape, as Telegraf's section sends), `rate` then counts frames. `noprof`: the same run
 * without the profiler (its overhead left out), for the CPU per 1,000 points only.
 *
 * `NAME=value` arguments go to the middleware's environment over these settings (e.g.
 * `WRITE_GZIP=false`), for a before/after of one setting on the same load.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { startInflux } from '../tests/helpers/influx.ts';
import { startMosquitto } from '../tests/helpers/mosquitto.ts';
import { selfTimes, type CpuProfile } from './lib/cpuprofile.ts';
import { cpuMeter } from './lib/proc.ts';
import {
  agentResult,
  BROKER_EXTRA,
  countPoints,
  REPO,
  startAgent,
  startMiddleware,
  waitForCount,
} from './lib/stack.ts';

const args = process.argv.slice(2);
const settings = Object.fromEntries(
  args
    .filter((a) => a.includes('='))
    .map((a) => [a.slice(0, a.indexOf('=')), a.slice(a.indexOf('=') + 1)]),
);
const [rateS = '20000', secondsS = '10', topS = '25', shape = 'group', mode = 'prof'] = args.filter(
  (a) => !a.includes('='),
);
const profiled = mode !== 'noprof';
const perMessage = shape === 'frame' ? 1 : 6;
const rate = Number(rateS);
const seconds = Number(secondsS);
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-profile-'));
const broker = await startMosquitto({ extraConfig: BROKER_EXTRA });
const influx = await startInflux();
try {
  const mw = await startMiddleware(
    {
      MQTT_URL: broker.url,
      MQTT_CLIENT_ID: `profile-ingest-${process.pid}`,
      INFLUX_URL: influx.url,
      INFLUX_BUCKET: influx.bucket,
      SPOOL_DIR: path.join(dir, 'spool'),
      WRITE_MODE: 'batch',
      ...settings,
    },
    path.join(dir, 'middleware.log'),
    profiled ? ['--cpu-prof', `--cpu-prof-dir=${dir}`] : [],
  );
  const arm = 'profile-arm';
  const cpu = cpuMeter(mw.child.pid);
  cpu.start();
  const pub = startAgent(
    'publisher',
    [
      broker.url,
      `arm/${arm}/status`,
      String(rate),
      String(seconds),
      String(Date.now()),
      '0',
      shape,
    ],
    path.join(dir, 'publisher.log'),
  );
  const r = await agentResult<{ sent: number; sendS: number }>(pub, seconds * 4000 + 30_000);
  const published = performance.now();
  const { got } = await waitForCount(
    () => countPoints(influx.url, influx.db, 'servo', 'pwm', arm),
    r.sent * perMessage,
    60_000,
  );
  const drainS = (performance.now() - published) / 1000;
  const c = cpu.stop();
  await mw.child.stop(20_000);
  const load = os
    .loadavg()
    .map((l) => l.toFixed(1))
    .join(' ');
  const file = fs.readdirSync(dir).find((f) => f.endsWith('.cpuprofile'));
  console.log(
    `${r.sent} ${shape}s in ${r.sendS.toFixed(1)} s (${Math.round(r.sent / r.sendS)}/s offered ${rate}), ` +
      `${got}/${r.sent * perMessage} points stored (the last ${drainS.toFixed(1)} s after the publisher ended); middleware CPU ${((c.cpuS * 1e6) / Math.max(1, got)).toFixed(2)} ms per 1,000 points; ` +
      `load ${load}; settings ${JSON.stringify(settings)}${file ? `; profile ${path.join(dir, file)}` : ''}`,
  );
  if (profiled) {
    if (!file) throw new Error(`no profile in ${dir}`);
    const { rows } = selfTimes(
      JSON.parse(fs.readFileSync(path.join(dir, file), 'utf8')) as CpuProfile,
      REPO,
    );
    const busy = rows.filter((x) => x.fn !== '(idle)');
    const busyMs = busy.reduce((s, x) => s + x.selfMs, 0);
    console.log(`self time, share of the busy samples (${busyMs.toFixed(0)} ms):`);
    for (const x of busy.slice(0, Number(topS)))
      console.log(`${((x.selfMs / busyMs) * 100).toFixed(1).padStart(5)} %  ${x.fn}`);
  }
} finally {
  await broker.dispose().catch(() => {});
  await influx.dispose().catch(() => {});
}
