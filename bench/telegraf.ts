/**
 * Section: Telegraf side by side (issue 19). What a user would pick instead of armtwin's
 * middleware: Telegraf's `mqtt_consumer` parsing the frames with its own grok parser, one metric
 * per servo reading, into the same InfluxDB. Both take the same frames from the same publisher
 * (bench/agents/publisher.ts, `frame` shape: one `$TIM`-stamped position frame per message, the
 * shape both can parse, QoS 0 as an arm sends), one after the other, each with batches of 1,000 points flushed every
 * second. A ramp of publish rates for each; a step passes when every frame is a point in
 * InfluxDB (counted per arm tag), the publisher kept the rate, and the backlog was written within
 * 1 s + max(2 s, D/4) of the last message. Each consumer's figure is its highest passing rate,
 * and CPU (utime + stime from /proc) per 1,000 frames at that rate.
 * Then the same for armtwin's usual message, a 6-servo group (`$TIM:t!{#000P…!…#005P…!}`), for
 * which Telegraf needs a configuration of its own: the `value` parser takes the payload as one
 * string and a Starlark processor splits it into one metric per servo (grok makes one metric per
 * line, and a group is one line).
 * Not the same work: the middleware also stores each frame's angle and checks every frame
 * against the contract; Telegraf stores the pulse width only.
 */
import fs from 'node:fs';
import {
  BATCH,
  FLUSH_MS,
  startArmtwin,
  startTelegraf,
  TELEGRAF,
  type Shape,
} from './lib/telegraf-consumers.ts';
import { ramp, type Step } from './lib/telegraf-ramp.ts';
import { compareRows } from './lib/telegraf-rows.ts';
import type { Section, SectionOutput } from './lib/types.ts';

export const telegrafSection: Section = {
  id: 'telegraf',
  title: 'Telegraf side by side: the same frames into the same InfluxDB',
  precheck() {
    return fs.existsSync(TELEGRAF)
      ? null
      : `${TELEGRAF} missing: run scripts/build-telegraf.sh (a custom build, about a minute)`;
  },
  async run(ctx): Promise<SectionOutput> {
    const seconds = ctx.quick ? 3 : 5;
    // Frames/s, for both shapes (a group carries 6).
    const rates = ctx.quick
      ? [4000, 16_000, 32_000, 64_000, 128_000, 192_000, 256_000]
      : [10_000, 20_000, 40_000, 60_000, 80_000, 100_000, 150_000, 200_000, 300_000];
    const t0 = { ms: Date.now() };
    const results: Record<Shape, Record<string, Step[]>> = { frame: {}, group: {} };
    for (const shape of ['frame', 'group'] as const) {
      for (const start of [startTelegraf, startArmtwin]) {
        const c = await start(ctx, shape);
        try {
          results[shape][c.name] = await ramp(ctx, c, rates, seconds, t0, shape);
        } finally {
          await c.stop();
        }
      }
    }
    return {
      rows: [...compareRows(results.frame, 'frame'), ...compareRows(results.group, 'group')],
      settings: {
        seconds,
        rates,
        batch: BATCH,
        flushMs: FLUSH_MS,
        publishQos: 0,
        subscribeQos: 1,
        shapes: ['frame', 'group'],
      },
      data: { steps: results },
    };
  },
};
