/**
 * Section 3: the seed's CPU experiment (seed 000 Fig. 11). One simulator at 6 servos × 250 Hz
 * (`armtwin sim --rate 250`), and two middlewares subscribed to it at the same time, one with
 * WRITE_MODE=sync (one write request per frame), one with WRITE_MODE=batch (defaults), each
 * into its own database — so both see the same stream on the same machine in the same seconds.
 * CPU = utime + stime from /proc over the window, as a share of one core. Points written and
 * dropped come from each middleware's /metrics.
 */
import fs from 'node:fs';
import path from 'node:path';
import { startMiddleware, startSim, type Middleware } from './lib/stack.ts';
import { cpuMeter, sleep } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { barChartSvg } from './lib/svg.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const ARM = 'bench-cpu';

export const cpuSection: Section = {
  id: 'cpu',
  title: 'Middleware CPU at 6 servos × 250 Hz: sync vs batch (seed 000 Fig. 11)',
  async run(ctx): Promise<SectionOutput> {
    const warmS = 5;
    const windowS = ctx.quick ? 20 : 60;
    const sim = await startSim(ctx.broker.url, ARM, 250, path.join(ctx.logDir, 'cpu-sim.log'));
    const mws: Record<'sync' | 'batch', Middleware> = {} as never;
    try {
      for (const mode of ['sync', 'batch'] as const) {
        mws[mode] = await startMiddleware(
          {
            MQTT_URL: ctx.broker.url,
            MQTT_CLIENT_ID: `bench-cpu-${mode}-${process.pid}`,
            INFLUX_URL: ctx.influx.url,
            INFLUX_BUCKET: `cpu_${mode}/autogen`,
            INFLUX_CREATE_BUCKET: 'true',
            SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, `spool-${mode}-`)),
            WRITE_MODE: mode,
          },
          path.join(ctx.logDir, `cpu-middleware-${mode}.log`),
        );
      }
      ctx.log(`cpu: warm-up ${warmS} s, then ${windowS} s with both middlewares`);
      await sleep(warmS * 1000);
      const meters = {
        sync: cpuMeter(mws.sync.child.pid),
        batch: cpuMeter(mws.batch.child.pid),
        sim: cpuMeter(sim.pid),
      };
      const m0 = { sync: await mws.sync.metrics(), batch: await mws.batch.metrics() };
      for (const m of Object.values(meters)) m.start();
      await sleep(windowS * 1000);
      const c = { sync: meters.sync.stop(), batch: meters.batch.stop(), sim: meters.sim.stop() };
      const m1 = { sync: await mws.sync.metrics(), batch: await mws.batch.metrics() };
      const d = (mode: 'sync' | 'batch', k: string) => (m1[mode][k] ?? 0) - (m0[mode][k] ?? 0);
      const per = (mode: 'sync' | 'batch') => ({
        cpuShareOfOneCore: round(c[mode].share, 4),
        cpuS: round(c[mode].cpuS, 3),
        windowS: round(c[mode].wallS, 2),
        framesPerS: round(d(mode, 'frames_total{kind="position"}') / c[mode].wallS, 1),
        pointsProducedPerS: round(d(mode, 'points_produced_total') / c[mode].wallS, 1),
        pointsWrittenPerS: round(d(mode, 'points_written_total') / c[mode].wallS, 1),
        writeRequests: d(mode, 'write_batches_total{result="ok"}'),
        droppedDelta: d(mode, 'points_dropped_total'),
        spoolPointsAtEnd: m1[mode].spool_points ?? 0,
        cpuMsPer1000Points: round(
          (c[mode].cpuS * 1e6) / Math.max(1, d(mode, 'points_produced_total')),
          3,
        ),
      });
      const sync = per('sync');
      const batch = per('batch');
      const ratio = batch.cpuShareOfOneCore / sync.cpuShareOfOneCore;
      const pct = (v: number) => `${fmt(v * 100, 1)} %`;
      const rows: Row[] = [
        {
          figure: 'Middleware CPU (share of one core), 6 × 250 Hz: batch vs sync',
          value: `batch ${pct(batch.cpuShareOfOneCore)} (${fmt(batch.pointsWrittenPerS, 0)} points/s written, ${batch.writeRequests} requests)`,
          baseline: `sync ${pct(sync.cpuShareOfOneCore)} (${fmt(sync.pointsWrittenPerS, 0)} points/s written, ${sync.writeRequests} requests)`,
          target: 'batch ≤ ¼ of sync',
          met: ratio <= 0.25,
        },
        {
          figure: 'batch ÷ sync CPU (seed 000 Fig. 11: 1.2 % ÷ 4.5 % = 0.27)',
          value: fmt(ratio, 3),
          baseline: '1.000',
          target: '≤ 0.25',
          met: ratio <= 0.25,
        },
        {
          figure: 'Points dropped in the window (sync / batch)',
          value: `${sync.droppedDelta} / ${batch.droppedDelta}`,
          baseline: `sim ${pct(c.sim.share)} CPU`,
          target: '0',
          met: sync.droppedDelta === 0 && batch.droppedDelta === 0,
        },
      ];
      const file = `${ctx.stamp}-cpu.svg`;
      fs.writeFileSync(
        path.join(ctx.resultsDir, file),
        barChartSvg({
          title: `Middleware CPU at 6 servos × 250 Hz, ${windowS} s, same stream (cf. seed 000 Fig. 11)`,
          xLabel: 'write mode',
          yLabel: '% of one core',
          categories: ['sync (one request per frame)', 'batch (1000 points / 5 s)'],
          series: [
            {
              name: 'middleware CPU',
              values: [
                round(sync.cpuShareOfOneCore * 100, 2),
                round(batch.cpuShareOfOneCore * 100, 2),
              ],
              colour: '#d95f02',
            },
          ],
          width: 480,
        }),
      );
      return {
        rows,
        plots: [{ file, title: 'CPU sync vs batch' }],
        settings: {
          rateHz: 250,
          servos: 6,
          warmS,
          windowS,
          concurrent: true,
          sync: 'WRITE_MODE=sync',
          batch: 'WRITE_MODE=batch, BATCH_SIZE 1000, FLUSH_INTERVAL_MS 5000',
        },
        data: { sync, batch, simCpuShare: round(c.sim.share, 4), ratio: round(ratio, 4) },
      };
    } finally {
      for (const m of Object.values(mws)) await m.child.stop();
      await sim.stop();
    }
  },
};
