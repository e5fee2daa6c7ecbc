/**
 * `--only twin`: the twin's fidelity, |sim − drawn| in degrees over all 6 servos, for each way
 * of drawing it (`?twin=predict`, the predictive twin; `?twin=interpolate`, the seed's) at the
 * contract's default 50 Hz state rate and at 250 Hz, each beside the ideal "draw the newest
 * sample received" renderer at the same frame instants (the baseline of the browser section).
 * Same method as bench/browser.ts: the built HUD in headless Chromium, the page probe
 * (./lib/page-probe.ts) records each rendered frame's wall time and drawn angles, this process
 * records the simulator's stream (its true trajectory) and publishes the scripted moves.
 */
import fs from 'node:fs';
import path from 'node:path';
import { sleep } from './lib/proc.ts';
import { serveStatic } from './lib/static.ts';
import type { ProbeResult } from './lib/page-probe.ts';
import { round, summarize } from './lib/stats.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';
import { SCRIPTED_TRAJECTORY, groupMove, startTrajectory } from './lib/trajectory.ts';
import { hudPrecheck, openHudBrowser } from './lib/hud-browser.ts';
import { openProbedHud, startProbe, stopProbe } from './lib/probed-hud.ts';
import { startRecordedArm } from './lib/recorded-arm.ts';
import type { StreamRecorder } from './lib/stream-recorder.ts';
import { frameErrors } from './lib/fidelity.ts';

const SERVOS = 6;
/** The browser section's scripted trajectory (./lib/trajectory.ts). */
const TRAJECTORY = SCRIPTED_TRAJECTORY;
const RATES = [50, 250] as const;
const MODES = ['predict', 'interpolate'] as const;

function fidelity(p: ProbeResult, rec: StreamRecorder) {
  const e = frameErrors(p, rec, SERVOS);
  return { fidelityDeg: summarize(e.drawn), drawNewestDeg: summarize(e.newest) };
}

/**
 * The frames with the largest error, each with where it fell: ms since the scripted move began
 * (as this process heard it), the servo, drawn and true angles, and the newest report's age.
 */
function worstFrames(p: ProbeResult, rec: StreamRecorder, moves: number[], count: number) {
  const n = p.servoCount;
  const all: { err: number; k: number; i: number; truth: number; shown: number }[] = [];
  for (let k = 0; k < p.frames; k++) {
    for (let i = 0; i < Math.min(n, SERVOS); i++) {
      const truth = rec.angleAt(i, p.wall[k]!);
      const shown = p.angles[k * n + i]!;
      if (Number.isFinite(truth) && Number.isFinite(shown))
        all.push({ err: Math.abs(shown - truth), k, i, truth, shown });
    }
  }
  all.sort((a, b) => b.err - a.err);
  return all.slice(0, count).map(({ err, k, i, truth, shown }) => {
    const w = p.wall[k]!;
    const move = moves.filter((m) => m <= w).pop();
    return {
      servo: i,
      errDeg: round(err, 3),
      shownDeg: round(shown, 2),
      trueDeg: round(truth, 2),
      msIntoMove: move === undefined ? null : round(w - move, 1),
      reportAgeMs: round(w - p.stamp[k]!, 1),
    };
  });
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
    const { browser, page, pageErrors } = await openHudBrowser(ctx.chromiumArgs);
    const data: Record<string, unknown> = {};
    const rows: Row[] = [];
    try {
      for (const rate of RATES) {
        const arm = `bench-twin-${rate}`;
        /** When each scripted move reached this process (epoch ms): where a frame is in its move. */
        const moves: number[] = [];
        const recorded = await startRecordedArm(ctx, {
          arm,
          rateHz: rate,
          servos: SERVOS,
          logName: `twin-sim-${rate}.log`,
          clientId: `bench-twin-${process.pid}-${rate}`,
          onControl: (r) => {
            if (r.on) moves.push(performance.timeOrigin + performance.now());
          },
        });
        const { client, rec } = recorded;
        let stop = () => {};
        try {
          for (const mode of MODES) {
            const url = `${web.url}?broker=${encodeURIComponent(ctx.broker.wsUrl)}&arm=${arm}&twin=${mode}`;
            ctx.log(`twin: ${rate} Hz, ${mode}, ${windowS} s`);
            await openProbedHud(page, url, 50, Math.round(windowS * 240));
            await sleep(2000);
            rec.clear();
            moves.length = 0;
            rec.on = true;
            await sleep(200);
            await startProbe(page);
            stop = startTrajectory(client, arm, TRAJECTORY);
            await sleep(windowS * 1000);
            stop();
            const probe = await stopProbe(page);
            await sleep(300);
            rec.on = false;
            const f = fidelity(probe, rec);
            const worst = worstFrames(probe, rec, moves, 5);
            data[`${mode}${rate}Hz`] = { ...f, frames: probe.frames, worst };
            // The raw record, for a closer look (kept with --keep-logs).
            fs.writeFileSync(
              path.join(ctx.logDir, `twin-${mode}${rate}Hz.json`),
              JSON.stringify({ probe, stamp: rec.stamp, pwm: rec.pwm, moves }),
            );
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
              groupMove(TRAJECTORY.poses[0]!, TRAJECTORY.moveMs),
              { qos: 1 },
            );
            await sleep(1200);
          }
        } finally {
          stop();
          await recorded.close();
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
