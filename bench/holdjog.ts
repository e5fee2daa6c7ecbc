/**
 * Section: hold-to-jog, release → stop. The HUD in headless Chromium holds the base (servo 000)
 * with a hold key (Q/A), a touch on its − / + button (CDP touch events), and a scripted gamepad
 * (stick pushed, right trigger held; `navigator.getGamepads` overridden), then lets go. Figures,
 * from the instant the bench lets go: the per-servo stop `#000PDST!` at a raw MQTT subscriber, and
 * the simulator's last position change (250 Hz reports, so ±4 ms). Baseline: the page stalls
 * instead of letting go (its main thread busy for 1.5 s with the key still down), so only the
 * keep-alive horizon stops the arm (docs/protocol.md § Hold-to-jog).
 */
import path from 'node:path';
import type { Page } from 'playwright-core';
import { serveStatic } from './lib/static.ts';
import { connectMqtt, startSim } from './lib/stack.ts';
import { sleep, until } from './lib/proc.ts';
import { hudPrecheck, hudReady, openHudBrowser, HUD_DIST } from './lib/hud-browser.ts';
import { summarize, type Summary } from './lib/stats.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const ARM = 'bench-holdjog';
const RATE_HZ = 250;
/** The keep-alive horizon of DEFAULT_HOLD_JOG_OPTIONS: a stalled page stops within it. */
const HORIZON_MS = 250;

/** Servo 000's reports and the control topic, with arrival times (epoch ms). */
class Watch {
  readonly reports: { at: number; pwm: number }[] = [];
  readonly control: { at: number; text: string }[] = [];
  get pwm(): number {
    return this.reports.at(-1)?.pwm ?? NaN;
  }
  feed(topic: string, text: string): void {
    const at = Date.now();
    if (topic.endsWith('/control')) this.control.push({ at, text });
    const m = /#000P(\d{3,4})!/.exec(text);
    if (topic.endsWith('/status') && m) this.reports.push({ at, pwm: Number(m[1]) });
  }
  /** When `#000PDST!` first arrived after `t0` (NaN if not). */
  stopAfter(t0: number): number {
    return this.control.find((c) => c.at >= t0 && c.text.includes('#000PDST!'))?.at ?? NaN;
  }
  /** When the position last changed after `t0` (t0 itself when it did not change). */
  lastChangeAfter(t0: number): number {
    let last = t0;
    for (let i = 1; i < this.reports.length; i++) {
      const r = this.reports[i]!;
      if (r.at >= t0 && r.pwm !== this.reports[i - 1]!.pwm) last = r.at;
    }
    return last;
  }
}

/** The page's scripted gamepad (as tests/e2e/gamepad.spec.ts injects it). */
const GAMEPAD_INIT = `(() => {
  const pad = { id: 'bench gamepad', index: 0, connected: true, mapping: 'standard', timestamp: 0,
    axes: [0, 0, 0, 0], buttons: Array.from({ length: 17 }, () => ({ pressed: false, touched: false, value: 0 })) };
  Object.defineProperty(Navigator.prototype, 'getGamepads', { configurable: true, value: () => [pad] });
  window.__pad = (axes, pressed) => {
    pad.axes = axes;
    pad.buttons = pad.buttons.map((_, i) => ({ pressed: pressed.includes(i), touched: false, value: pressed.includes(i) ? 1 : 0 }));
  };
})();`;

type Kind = 'keyboard' | 'touch' | 'gamepad';

interface Input {
  press(dir: 1 | -1): Promise<void>;
  release(): Promise<void>;
}

async function inputs(page: Page): Promise<Record<Kind, Input>> {
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Emulation.setTouchEmulationEnabled', { enabled: true, maxTouchPoints: 1 });
  let key = 'q';
  const centre = async (dir: 1 | -1) => {
    const b = await page.getByTestId(`hold-0-${dir > 0 ? 'plus' : 'minus'}`).boundingBox();
    if (!b) throw new Error('no hold button for the base');
    return { x: b.x + b.width / 2, y: b.y + b.height / 2 };
  };
  const pad = (axes: number[], pressed: number[]) =>
    page.evaluate(
      ([a, p]) => (window as unknown as { __pad(a: number[], p: number[]): void }).__pad(a!, p!),
      [axes, pressed],
    );
  return {
    keyboard: {
      async press(dir) {
        key = dir > 0 ? 'q' : 'a';
        await page.keyboard.down(key);
      },
      release: () => page.keyboard.up(key),
    },
    touch: {
      async press(dir) {
        const p = await centre(dir);
        await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [p] });
      },
      release: () =>
        cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] }).then(() => {}),
    },
    gamepad: {
      press: (dir) => pad([dir, 0, 0, 0], [7]),
      release: () => pad([0, 0, 0, 0], []),
    },
  };
}

/** Holds, lets go, and measures: ms to the stop frame and to the last position change. */
async function once(w: Watch, input: Input, dir: 1 | -1) {
  const start = w.pwm;
  await input.press(dir);
  if (!(await until(() => Math.abs(w.pwm - start) > 15, 5000, 5)))
    throw new Error('the base did not move while held');
  await sleep(300);
  const t0 = Date.now();
  await input.release();
  await until(() => Number.isFinite(w.stopAfter(t0)), 3000, 2);
  await sleep(700); // the arm settles; reports keep coming
  return { stopFrameMs: w.stopAfter(t0) - t0, stillMs: w.lastChangeAfter(t0) - t0 };
}

/** The baseline: the page stalls with the key down; ms from the stall to the last change. */
async function stall(page: Page, w: Watch): Promise<number> {
  const start = w.pwm;
  await page.keyboard.down('q');
  await until(() => Math.abs(w.pwm - start) > 15, 5000, 5);
  await sleep(300);
  const t0 = Date.now();
  const busy = page.evaluate(() => {
    const end = performance.now() + 1500;
    while (performance.now() < end);
  });
  await busy;
  const still = w.lastChangeAfter(t0) - t0;
  await page.keyboard.up('q');
  await sleep(700);
  // back where it came from, for the next one
  await page.keyboard.down('a');
  await until(() => w.pwm <= start, 5000, 5);
  await page.keyboard.up('a');
  await sleep(500);
  return still;
}

const ms = (s: Summary) => `p50 ${fmt(s.p50, 0)} ms, p99 ${fmt(s.p99, 0)} ms (n = ${s.n})`;

export const holdJogSection: Section = {
  id: 'holdjog',
  title: 'Hold-to-jog: release → stop (keyboard, touch, gamepad) vs a stalled page',
  precheck() {
    return hudPrecheck();
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const reps = ctx.quick ? 8 : 25;
    const web = await serveStatic(HUD_DIST);
    const sim = await startSim(ctx.broker.url, ARM, RATE_HZ, path.join(ctx.logDir, 'holdjog.log'));
    const client = await connectMqtt(ctx.broker.url, `bench-holdjog-${process.pid}`);
    const w = new Watch();
    client.on('message', (topic, payload) => w.feed(topic, payload.toString('latin1')));
    await client.subscribeAsync([`arm/${ARM}/status`, `arm/${ARM}/control`], { qos: 0 });
    const { browser, page, pageErrors } = await openHudBrowser(ctx.chromiumArgs);
    try {
      await page.context().addInitScript({ content: GAMEPAD_INIT });
      await page.goto(
        `${web.url}?broker=${encodeURIComponent(ctx.broker.wsUrl)}&arm=${ARM}&role=operator`,
      );
      await hudReady(page);
      await page.getByTestId('hold-speed').selectOption('30');
      await page.locator('body').click({ position: { x: 5, y: 5 } });
      const byKind = await inputs(page);
      const results: Record<string, { stopFrameMs: number[]; stillMs: number[] }> = {};
      for (const kind of ['keyboard', 'touch', 'gamepad'] as Kind[]) {
        ctx.log(`holdjog: ${reps} × ${kind}`);
        const r = (results[kind] = { stopFrameMs: [] as number[], stillMs: [] as number[] });
        for (let i = 0; i < reps; i++) {
          const m = await once(w, byKind[kind], i % 2 ? -1 : 1);
          r.stopFrameMs.push(m.stopFrameMs);
          r.stillMs.push(m.stillMs);
        }
      }
      ctx.log(`holdjog: ${Math.ceil(reps / 2)} stalls`);
      const stalls: number[] = [];
      for (let i = 0; i < Math.ceil(reps / 2); i++) stalls.push(await stall(page, w));
      if (pageErrors.length) throw new Error(`page errors: ${pageErrors.join('; ')}`);
      const stallS = summarize(stalls);
      const rows: Row[] = (['keyboard', 'touch', 'gamepad'] as Kind[]).flatMap((kind) => {
        const stop = summarize(results[kind]!.stopFrameMs);
        const still = summarize(results[kind]!.stillMs);
        return [
          {
            figure: `Hold-to-jog, ${kind}: release → arm still (last position change, ${RATE_HZ} Hz reports)`,
            value: ms(still),
            baseline: `page stalled instead: ${ms(stallS)}`,
            target: `p99 ≤ ${HORIZON_MS} ms (one keep-alive horizon)`,
            met: still.n === reps && still.p99 <= HORIZON_MS,
          },
          {
            figure: `Hold-to-jog, ${kind}: release → #000PDST! at a subscriber`,
            value: ms(stop),
            baseline: '—',
            target: 'reported',
            met: null,
          },
        ];
      });
      return {
        rows,
        settings: { reps, rateHz: RATE_HZ, speedDegPerS: 30, horizonMs: HORIZON_MS },
        data: { results, stalls: stallS, rawStalls: stalls },
      };
    } finally {
      await browser.close().catch(() => {});
      await client.endAsync().catch(() => {});
      await sim.stop();
      await web.close();
    }
  },
};
