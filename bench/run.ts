/**
 * `npm run bench [-- --quick] [-- --only rtt,ik] [-- --keep-logs] [-- --only soak --soak-minutes 30]`: runs the benchmark
 * sections on real services (a throwaway Mosquitto and influxd from tests/helpers, the
 * simulator, the middleware, headless Chromium), each figure beside its baseline in the same
 * run, and writes bench/results/<stamp>.json, SVG plots there, and the generated block of
 * BENCHMARKS.md. A section that cannot run is reported as skipped or failed with the reason;
 * every child process is killed at the end.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  startInflux,
  startMosquitto,
  type InfluxService,
  type MosquittoService,
} from '../tests/helpers/services.ts';
import { machineInfo, versions } from './lib/machine.ts';
import { killAll, liveChildren } from './lib/proc.ts';
import {
  markdown,
  newestRunOf,
  updateBenchmarksMd,
  writeJson,
  type CarriedSection,
  type RunRecord,
} from './lib/report.ts';
import { BROKER_EXTRA, REPO } from './lib/stack.ts';
import { parseBenchArgs } from './lib/args.ts';
import { HUD_DIST } from './lib/hud-browser.ts';
import type { BenchContext, Section, SectionResult } from './lib/types.ts';
import { ikSection } from './ik.ts';
import { zonesSection } from './zones.ts';
import { rttSection } from './rtt.ts';
import { ingestSection } from './ingest.ts';
import { cpuSection } from './cpu.ts';
import { browserSection } from './browser.ts';
import { deadmanSection } from './deadman.ts';
import { cameraSection } from './camera.ts';
import { telegrafSection } from './telegraf.ts';
import { holdJogSection } from './holdjog.ts';
import { handoverSection } from './handover.ts';
import { soakSection } from './soak.ts';
import { twinSection } from './twin.ts';
import { ros2Section } from './ros2.ts';
import { foxgloveSection } from './foxglove.ts';
import { lerobotSection } from './lerobot.ts';
import { fleetSection } from './fleet.ts';
import { clusterSection } from './cluster.ts';
import { datasetSection } from './dataset.ts';
import { CHROMIUM_ARGS, GPU_CHROMIUM_ARGS } from '../tests/helpers/chromium.ts';

const SECTIONS: Section[] = [
  rttSection,
  ingestSection,
  cpuSection,
  browserSection,
  twinSection,
  deadmanSection,
  ikSection,
  zonesSection,
  cameraSection,
  telegrafSection,
  holdJogSection,
  handoverSection,
  ros2Section,
  foxgloveSection,
  lerobotSection,
  fleetSection,
  clusterSection,
  datasetSection,
  soakSection,
];
/**
 * Sections left out of a run without `--only`: the soak (alone it takes `--soak-minutes`, 30
 * min), the fleet (issue 34 item 3: two brokers' ramps up to 1,600 arms, and the page's
 * fleet runs again) and the cluster (a 3-node NATS cluster per step, up to 100 arms through a
 * node's kill: minutes); a default run's table carries their newest run.
 */
const NOT_BY_DEFAULT = new Set(['soak', 'fleet', 'cluster']);
/** Broker settings for every section (recorded in the JSON): see BENCHMARKS.md on Nagle. */
const NEEDS_BROKER = new Set([
  'rtt',
  'ingest',
  'cpu',
  'browser',
  'deadman',
  'camera',
  'telegraf',
  'holdjog',
  'handover',
  'soak',
  'twin',
  'lerobot',
  'fleet',
]);
const NEEDS_INFLUX = new Set(['ingest', 'cpu', 'telegraf', 'soak', 'fleet', 'cluster']);

const log = (m: string) => console.log(`[bench ${new Date().toISOString().slice(11, 19)}] ${m}`);

async function main(): Promise<number> {
  const args = parseBenchArgs(
    process.argv.slice(2),
    SECTIONS.map((s) => s.id),
    HUD_DIST,
  );
  const sections = SECTIONS.filter((s) =>
    args.only ? args.only.has(s.id) : !NOT_BY_DEFAULT.has(s.id),
  );
  const startedAt = new Date();
  const stamp = startedAt.toISOString().replace(/[:]/g, '-').slice(0, 19);
  const resultsDir = path.join(REPO, 'bench', 'results');
  fs.mkdirSync(resultsDir, { recursive: true });
  const logDir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-bench-'));
  const machine: Record<string, unknown> = machineInfo();
  log(`${args.quick ? 'quick' : 'full'} run ${stamp}: ${sections.map((s) => s.id).join(', ')}`);

  let broker: MosquittoService | undefined;
  let influx: InfluxService | undefined;
  const results: RunRecord['sections'] = {};
  try {
    if (sections.some((s) => NEEDS_BROKER.has(s.id))) {
      log('starting Mosquitto');
      broker = await startMosquitto({ extraConfig: BROKER_EXTRA });
    }
    if (sections.some((s) => NEEDS_INFLUX.has(s.id))) {
      log('starting influxd');
      influx = await startInflux();
    }
    const ctx: BenchContext = {
      quick: args.quick,
      resultsDir,
      stamp,
      logDir,
      broker: broker!,
      influx: influx!,
      log,
      hudDist: args.hudDist,
      soakMinutes: args.soakMinutes,
      chromiumArgs: args.gpu ? GPU_CHROMIUM_ARGS : CHROMIUM_ARGS,
    };
    for (const s of sections) {
      const t0 = performance.now();
      const dur = () => Math.round((performance.now() - t0) / 100) / 10;
      const skip = s.precheck?.() ?? null;
      let r: SectionResult;
      if (skip) r = { status: 'skipped', reason: skip, durationS: 0 };
      else {
        log(`§ ${s.id}: ${s.title}`);
        try {
          r = { status: 'ok', ...(await s.run(ctx)), durationS: 0 };
          r.durationS = dur();
        } catch (err) {
          const e = err as Error;
          r = {
            status: 'failed',
            reason: e.message.split('\n')[0] ?? String(err),
            durationS: dur(),
          };
          log(`§ ${s.id} failed: ${e.stack ?? e.message}`);
        }
      }
      log(`§ ${s.id}: ${r.status} in ${r.durationS} s${r.status !== 'ok' ? ` (${r.reason})` : ''}`);
      results[s.id] = { ...r, title: s.title };
    }
    machine.loadAverageAtEnd = os.loadavg().map((v) => Math.round(v * 100) / 100);
    const run: RunRecord = {
      stamp,
      startedAt: startedAt.toISOString(),
      finishedAt: new Date().toISOString(),
      mode: args.quick ? 'quick' : 'full',
      command: `npm run bench${process.argv.length > 2 ? ` -- ${process.argv.slice(2).join(' ')}` : ''}`,
      machine,
      versions: await versions(influx?.url),
      sections: results,
    };
    // A default run's table keeps the sections it leaves out (the soak) from their newest run.
    const carried: Record<string, CarriedSection> = {};
    if (!args.only)
      for (const id of NOT_BY_DEFAULT) {
        const c = newestRunOf(resultsDir, id);
        if (c) carried[id] = c;
      }
    if (Object.keys(carried).length)
      run.carried = Object.fromEntries(Object.entries(carried).map(([id, c]) => [id, c.stamp]));
    const json = writeJson(resultsDir, run);
    const rel = path.relative(REPO, json);
    const shown = SECTIONS.filter((s) => sections.includes(s) || carried[s.id]);
    const block = markdown(run, shown, rel, carried);
    if (args.md) await updateBenchmarksMd(path.join(REPO, 'BENCHMARKS.md'), block);
    console.log(`\n${block}\n`);
    log(`wrote ${rel}${args.md ? ' and BENCHMARKS.md' : ''}`);
    return Object.values(results).some((r) => r.status === 'failed') ? 1 : 0;
  } finally {
    await broker?.dispose().catch(() => {});
    await influx?.dispose().catch(() => {});
    const left = liveChildren();
    killAll();
    if (left) log(`killed ${left} child process(es) still running`);
    if (args.keepLogs) log(`logs kept in ${logDir}`);
    else fs.rmSync(logDir, { recursive: true, force: true });
  }
}

main().then(
  (code) => process.exit(code),
  (err: unknown) => {
    console.error(err instanceof Error ? err.message : err);
    killAll();
    process.exit(2);
  },
);
