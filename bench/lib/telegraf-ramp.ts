/**
 * One ramp of the Telegraf section (bench/telegraf.ts): rising publish rates against one
 * consumer until a step fails. A step passes when every frame is a point in InfluxDB (counted
 * per arm tag), the publisher kept the rate, and the backlog was written within
 * 1 s + max(2 s, D/4) of the last message; each step records the consumer's CPU.
 */
import path from 'node:path';
import { agentResult, countPoints, startAgent, waitForCount } from './stack.ts';
import { cpuMeter } from './proc.ts';
import { round } from './stats.ts';
import { stepVerdict } from './zero-loss.ts';
import type { BenchContext } from './types.ts';
import { FLUSH_MS, FRAMES_PER_MESSAGE, type Consumer, type Shape } from './telegraf-consumers.ts';

export interface Step {
  offeredPerS: number;
  sent: number;
  publishedPerS: number;
  stored: number;
  drainS: number;
  cpuPer1000Ms: number;
  /** The consumer's CPU over the step: cores (utime + stime ÷ wall), and the wall, s. */
  cpuCores: number;
  wallS: number;
  passed: boolean;
  why: string;
}

/** One ramp: rising rates until a step fails (or the list ends). */
export async function ramp(
  ctx: BenchContext,
  c: Consumer,
  rates: readonly number[],
  seconds: number,
  t0: { ms: number },
  shape: Shape,
): Promise<Step[]> {
  const steps: Step[] = [];
  const per = FRAMES_PER_MESSAGE[shape];
  for (const frames of rates) {
    // `rates` are frames/s; the publisher sends messages of `per` frames.
    const rate = Math.round(frames / per);
    const arm = `${c.prefix}-${frames}`;
    ctx.log(`telegraf: ${c.name}, ${frames} frames/s (${shape}) for ${seconds} s`);
    const cpu = cpuMeter(c.pid);
    const pub = startAgent(
      'publisher',
      [
        ctx.broker.url,
        `arm/${arm}/status`,
        String(rate),
        String(seconds),
        String(t0.ms),
        '0',
        shape,
      ],
      path.join(ctx.logDir, `telegraf-pub-${c.prefix}-${frames}.log`),
    );
    cpu.start();
    let r: { sent: number; sendS: number };
    try {
      r = await agentResult<{ sent: number; sendS: number }>(pub, seconds * 4000 + 30_000);
    } catch (err) {
      await pub.stop();
      cpu.stop();
      const why = `the publisher did not finish (${(err as Error).message})`;
      steps.push({
        offeredPerS: frames,
        sent: 0,
        publishedPerS: 0,
        stored: 0,
        drainS: NaN,
        cpuPer1000Ms: NaN,
        cpuCores: NaN,
        wallS: NaN,
        passed: false,
        why,
      });
      break;
    }
    await pub.exited;
    const pubEnd = performance.now();
    t0.ms += (shape === 'frame' ? Math.ceil(r.sent / 6) : r.sent) + 1000;
    const sentFrames = r.sent * per;
    const { got } = await waitForCount(
      () => countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm),
      sentFrames,
      FLUSH_MS + 30_000,
      FLUSH_MS + 5000,
    );
    const drainS = (performance.now() - pubEnd) / 1000;
    const used = cpu.stop();
    const why = stepVerdict({
      rate,
      sent: r.sent,
      sendS: r.sendS,
      missing: sentFrames - got,
      unit: 'frames',
      drainS,
      drainLimitS: FLUSH_MS / 1000 + Math.max(2, seconds / 4),
    });
    steps.push({
      offeredPerS: frames,
      sent: sentFrames,
      publishedPerS: Math.round(sentFrames / r.sendS),
      stored: got,
      drainS: round(drainS, 2),
      cpuPer1000Ms: round((used.cpuS * 1000 * 1000) / Math.max(1, got), 3),
      cpuCores: round(used.share, 3),
      wallS: round(used.wallS, 2),
      passed: why === '',
      why,
    });
    if (why) break;
  }
  return steps;
}
