/**
 * `--only twin`: the twin's fidelity, |sim − drawn| in degrees over all 6 servos, for each way
 * of drawing it (`?twin=predict`, the predictive twin; `?twin=interpolate`, the seed's) at the
 * contract's default 50 Hz state rate and at 250 Hz, each beside the ideal "draw the newest
 * sample received" renderer at the same frame instants (the baseline of the browser section).
 * Same method as bench/browser.ts: the built HUD in headless Chromium, the page probe
 * (./lib/page-probe.ts) records each rendered frame's wall time and drawn angles, this process
 * records the simulator's stream (its true trajectory) and publishes the scripted moves.
 */
import path from 'node:path';
import { connectMqtt, startSim } from './lib/stack.ts';
import { sleep } from './lib/proc.ts';
import { serveStatic } from './lib/static.ts';
import { installProbe, type ProbeResult } from './lib/page-probe.ts';
import { summarize } from './lib/stats.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';
import { startTrajectory, type Trajectory } from './lib/trajectory.ts';
import { hudPrecheck, openHudBrowser, openLiveHud } from './lib/hud-browser.ts';
import { StreamRecorder } from './lib/stream-recorder.ts';

const SERVOS = 6;
/** The browser section's scripted trajectory (bench/browser.ts). */
const TRAJECTORY: Trajectory = {
  poses: [
    [1500, 1500, 1500, 1500, 1500, 1500],
    [1900, 1300, 1200, 1700, 1650, 1800],
    [1100, 1700, 1800, 1300, 1350, 1600],
    [1500, 1200, 1400, 1900, 1500, 1500],
  ],
  moveMs: 1000,
  stepMs: 1500,
};
const RATES = [50, 250] as const;
const MODES = ['predict', 'interpolate'] as const;

function fidelity(p: ProbeResult, rec: StreamRecorder) {
  const n = p.servoCount;
  const err: number[] = [];
  const newest: number[] = [];
  for (let k = 0; k < p.frames; k++) {
    const w = p.wall[k]!;
    const s = p.stamp[k]!;
    for (let i = 0; i < Math.min(n, SERVOS); i++) {
      const truth = rec.angleAt(i, w);
      const shown = p.angles[k * n + i]!;
      if (!Number.isFinite(truth) || !Number.isFinite(shown)) continue;
      err.push(Math.abs(shown - truth));
      const held = rec.angleAt(i, s);
      if (Number.isFinite(held)) newest.push(Math.abs(held - truth));
    }
  }
  return { fidelityDeg: summarize(err), drawNewestDeg: summarize(newest) };
}

export const twinSection: Section = {
  id: 'twin',
  title: 'Twin fidelity: predicted vs the seed’s interpolation, 50 Hz and 250 Hz',
  precheck() {
    return hudPrecheck();
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const windowS = ctx.quick ? 12 : 30;
    const web = await serveStatic(ctx.hudDist);
    const { browser, page, pageErrors } = await openHudBrowser();
    const data: Record<string, unknown> = {};
    const rows: Row[] = [];
    try {
      for (const rate of RATES) {
        const arm = `bench-twin-${rate}`;
        const sim = await startSim(
          ctx.broker.url,
          arm,
          rate,
          path.join(ctx.logDir, `twin-sim-${rate}.log`),
        );
        const client = await connectMqtt(ctx.broker.url, `bench-twin-${process.pid}-${rate}`);
        const rec = new StreamRecorder(SERVOS);
        client.on('message', (_t, payload) => rec.feed(payload));
        await client.subscribeAsync(`arm/${arm}/status`, { qos: 0 });
        let stop = () => {};
        try {
          for (const mode of MODES) {
            const url = `${web.url}?broker=${encodeURIComponent(ctx.broker.wsUrl)}&arm=${arm}&twin=${mode}`;
            ctx.log(`twin: ${rate} Hz, ${mode}, ${windowS} s`);
            await openLiveHud(page, url, 50);
            if (!(await page.evaluate(installProbe, Math.round(windowS * 240))))
              throw new Error('window.__armtwin has no store/viewer.renderer to probe');
            await sleep(2000);
            rec.clear();
            rec.on = true;
            await sleep(200);
            await page.evaluate(() =>
              (window as unknown as { __benchProbe: { start(): void } }).__benchProbe.start(),
            );
            stop = startTrajectory(client, arm, TRAJECTORY);
            await sleep(windowS * 1000);
            stop();
            const probe = await page.evaluate(() =>
              (window as unknown as { __benchProbe: { stop(): ProbeResult } }).__benchProbe.stop(),
            );
            await sleep(300);
            rec.on = false;
            const f = fidelity(probe, rec);
            data[`${mode}${rate}Hz`] = { ...f, frames: probe.frames };
            rows.push({
              figure: `Twin fidelity at ${rate} Hz, ${mode === 'predict' ? 'predicted (default)' : 'seed’s interpolation'}: |sim − drawn| ° (mean / max)`,
              value: `${fmt(f.fidelityDeg.mean, 3)} / ${fmt(f.fidelityDeg.max, 2)} (${probe.frames} frames)`,
              baseline: `draw-newest-sample ${fmt(f.drawNewestDeg.mean, 3)} / ${fmt(f.drawNewestDeg.max, 2)}`,
              target:
                mode === 'predict'
                  ? 'mean ≤ 0.25°, max ≤ 1.5°, ≥ 3× better than draw-newest'
                  : 'reported',
              met:
                mode === 'predict'
                  ? f.fidelityDeg.mean <= 0.25 &&
                    f.fidelityDeg.max <= 1.5 &&
                    f.fidelityDeg.mean * 3 <= f.drawNewestDeg.mean
                  : null,
            });
            // Back to rest before the next mode.
            await client.publishAsync(
              `arm/${arm}/control`,
              `{${TRAJECTORY.poses[0]!.map((v, i) => `#00${i}P${v}T1000!`).join('')}}`,
              { qos: 1 },
            );
            await sleep(1200);
          }
        } finally {
          stop();
          await client.endAsync().catch(() => {});
          await sim.stop();
        }
      }
      return {
        rows,
        plots: [],
        settings: { rates: RATES, modes: MODES, windowS, servos: SERVOS, trajectory: TRAJECTORY },
        data: { ...data, pageErrors: pageErrors.slice(0, 10) },
      };
    } finally {
      await browser.close().catch(() => {});
      await web.close();
    }
  },
};
