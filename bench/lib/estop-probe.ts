/**
 * The emergency stop measured from outside the page (issue 17 item 3): Playwright's mouse and
 * keyboard through CDP on the HUD's "Emergency stop" button and the Escape key, and an MQTT
 * subscriber on the arm's control topic: Mosquitto's own `mosquitto_sub`, in a process of its
 * own, which stamps each message as it takes it (`-F '%U'`, the Unix time in ns), so neither
 * this process's garbage collection nor the CDP events it parses delay the arrival. One sample:
 * the time from dispatching the first input of the gesture (the mouse button's press, released
 * at once after it, as Playwright's `click` does; the Escape key's press) to `#255PDST!`
 * arriving at the subscriber (epoch ms: this process's `performance.timeOrigin + now()`, the
 * subscriber's Unix time). Whatever renders the page (main thread or a worker) and whichever
 * event the page stops on (`pointerdown` or `click`), the probe sees only input and the wire.
 * Between samples the arm is set moving again (the caller's `rearm`, a move on the control
 * topic) and a random 200–500 ms pause puts the next input at another phase of the page's frame.
 */
import readline from 'node:readline';
import type { MqttClient } from 'mqtt';
import type { Page } from 'playwright-core';
import { sleep, spawnChild } from './proc.ts';
import { connectMqtt } from './stack.ts';
import { summarize } from './stats.ts';

export const STOP_FRAME = '#255PDST!';

export type StopInput = 'click' | 'escape' | 'node';

/**
 * Where one page stop's time went, ms, from the bench's clock and the page's (both epoch ms:
 * `performance.timeOrigin + performance.now()`, offset measured by `page.evaluate` round trips):
 * `dispatch` t0 → the input event's `timeStamp` (Playwright → CDP → the browser made the event);
 * `page` timeStamp → the stop's `WebSocket.send` (the event waiting for the page's main thread,
 * and the handler); of that, `queue` timeStamp → the first listener on `window` (NaN when the
 * HUD's own listener comes first, as for keydown); `wire` send → the subscriber (the browser's
 * socket, the broker, the subscriber); `input` the event's `timeStamp` → the subscriber (the
 * stop as the browser's own input clock sees it: all but Playwright's dispatch). NaN where the
 * page saw nothing.
 */
export interface StopBreakdown {
  total: number;
  input: number;
  dispatch: number;
  page: number;
  queue: number;
  wire: number;
}

export interface StopProbe {
  /** `n` samples of input → `#255PDST!` at the subscriber, ms (NaN for a stop that never came). */
  measure(input: StopInput, n: number, rearm: () => Promise<void>): Promise<number[]>;
  /** The breakdown of the last `measure`'s page samples (empty for `node`). */
  breakdown(): StopBreakdown[];
  close(): Promise<void>;
}

interface StopTrace {
  /** The first pointerdown / keydown: its timeStamp and the listener's entry, page ms. */
  event: { ts: number; at: number } | null;
  /** When a WebSocket frame holding the stop was sent, page ms. */
  sent: number;
}
type TracedWindow = Window & { __stopTrace?: StopTrace };

/** Runs in the page: notes the first input event and the stop's `WebSocket.send`. */
function installStopTrace(stop: string): void {
  const w = window as TracedWindow;
  if (w.__stopTrace) return;
  const trace: StopTrace = { event: null, sent: NaN };
  w.__stopTrace = trace;
  const note = (e: Event): void => {
    if (!trace.event) trace.event = { ts: e.timeStamp, at: performance.now() };
  };
  window.addEventListener('pointerdown', note, { capture: true });
  window.addEventListener('keydown', note, { capture: true });
  const send = WebSocket.prototype.send;
  const code = Array.from(stop, (c) => c.charCodeAt(0));
  const holds = (b: Uint8Array): boolean => {
    outer: for (let i = 0; i + code.length <= b.length; i++) {
      for (let j = 0; j < code.length; j++) if (b[i + j] !== code[j]) continue outer;
      return true;
    }
    return false;
  };
  WebSocket.prototype.send = function (data) {
    const at = performance.now();
    const bytes =
      data instanceof ArrayBuffer
        ? new Uint8Array(data)
        : ArrayBuffer.isView(data)
          ? new Uint8Array(data.buffer, data.byteOffset, data.byteLength)
          : null;
    if (Number.isNaN(trace.sent) && bytes && bytes.length < 256 && holds(bytes)) trace.sent = at;
    return send.call(this, data);
  };
}

/** page epoch ms − bench epoch ms, the best of a few round trips. */
async function pageClockOffset(page: Page): Promise<number> {
  let best = { rtt: Infinity, off: 0 };
  for (let i = 0; i < 10; i++) {
    const a = performance.timeOrigin + performance.now();
    const p = await page.evaluate(() => performance.timeOrigin + performance.now());
    const b = performance.timeOrigin + performance.now();
    if (b - a < best.rtt) best = { rtt: b - a, off: p - (a + b) / 2 };
  }
  return best.off;
}

export async function startStopProbe(
  brokerUrl: string,
  arm: string,
  page: Page,
  publisher: MqttClient,
): Promise<StopProbe> {
  const topic = `arm/${arm}/control`;
  const sub = await startStampingSubscriber(brokerUrl, topic);
  let waiting: ((t: number) => void) | null = null;
  sub.onMessage = (epochMs, payload) => {
    if (waiting && payload.includes(STOP_FRAME)) {
      const w = waiting;
      waiting = null;
      // Epoch ms → this process's performance.now().
      w(epochMs - performance.timeOrigin);
    }
  };

  const button = page.getByRole('button', { name: 'Emergency stop' });
  await page.evaluate(installStopTrace, STOP_FRAME);
  const origin = await page.evaluate(() => performance.timeOrigin);
  let parts: StopBreakdown[] = [];
  return {
    breakdown: () => parts,
    async measure(input, n, rearm) {
      const out: number[] = [];
      parts = [];
      const offset = await pageClockOffset(page);
      for (let i = 0; i < n; i++) {
        await rearm();
        await sleep(200 + Math.random() * 300);
        let timer: ReturnType<typeof setTimeout> | undefined;
        const arrived = new Promise<number>((resolve) => {
          waiting = resolve;
          timer = setTimeout(() => resolve(NaN), 3000);
        });
        await page.evaluate(() => {
          const t = (window as TracedWindow).__stopTrace;
          if (t) Object.assign(t, { event: null, sent: NaN });
        });
        let t0: number;
        if (input === 'click') {
          const box = await button.boundingBox();
          if (!box) throw new Error('the Emergency stop button is not on screen');
          await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
          t0 = performance.now();
          await page.mouse.down();
          await page.mouse.up();
        } else if (input === 'escape') {
          t0 = performance.now();
          await page.keyboard.down('Escape');
          await page.keyboard.up('Escape');
        } else {
          t0 = performance.now();
          publisher.publish(topic, STOP_FRAME, { qos: 1 });
        }
        const t1 = await arrived;
        clearTimeout(timer);
        waiting = null;
        out.push(t1 - t0);
        if (input !== 'node') {
          const t = await page.evaluate(() => (window as TracedWindow).__stopTrace ?? null);
          // Page ms → bench ms: page epoch minus the clocks' offset, minus the bench's origin.
          const bench = (pageMs: number) => origin + pageMs - offset - performance.timeOrigin;
          const ev = t?.event;
          parts.push({
            total: t1 - t0,
            input: ev ? t1 - bench(ev.ts) : NaN,
            dispatch: ev ? bench(ev.ts) - t0 : NaN,
            page: ev && t ? t.sent - ev.ts : NaN,
            queue: ev && t && ev.at <= t.sent ? ev.at - ev.ts : NaN,
            wire: t ? t1 - bench(t.sent) : NaN,
          });
        }
      }
      return out;
    },
    async close() {
      sub.close();
    },
  };
}

interface StampingSubscriber {
  /** Each message: when the subscriber took it (Unix epoch ms) and its payload. */
  onMessage: (epochMs: number, payload: string) => void;
  close(): void;
}

/**
 * `mosquitto_sub` on `topic`, printing each message's arrival time; resolves once subscribed.
 * A tracked child (./proc.ts): the run kills it at the end whatever happened.
 */
async function startStampingSubscriber(
  brokerUrl: string,
  topic: string,
): Promise<StampingSubscriber> {
  const u = new URL(brokerUrl);
  // A topic of its own tells when it is subscribed (nothing bogus on the arm's topic).
  const ready = `bench/estop-sub/${process.pid}/${Date.now()}`;
  const args = ['-h', u.hostname, '-p', u.port || '1883', '-q', '0', '-F', '%U %t %p'];
  args.push('-t', topic, '-t', ready, '-i', `bench-estop-sub-${process.pid}-${Date.now()}`);
  const child = spawnChild('mosquitto_sub', args, { stdout: 'pipe' });
  const s: StampingSubscriber = {
    onMessage: () => {},
    close: () => void child.stop(),
  };
  let seen = false;
  readline.createInterface({ input: child.proc.stdout! }).on('line', (line) => {
    const [stamp = '', t = '', ...rest] = line.split(' ');
    if (t === ready) return void (seen = true);
    const [sec, ns = '0'] = stamp.split('.');
    s.onMessage(Number(sec) * 1000 + Number(ns.padEnd(9, '0')) / 1e6, rest.join(' '));
  });
  const pub = await connectMqtt(brokerUrl, `bench-estop-ready-${process.pid}`);
  try {
    const deadline = Date.now() + 10_000;
    while (!seen) {
      const code = child.proc.exitCode;
      if (code !== null || Date.now() > deadline) {
        s.close();
        throw new Error(
          `mosquitto_sub did not subscribe to ${topic}: ${code !== null ? `exit code ${code}` : 'timed out'}`,
        );
      }
      await pub.publishAsync(ready, 'ready', { qos: 0 });
      await sleep(100);
    }
  } finally {
    await pub.endAsync().catch(() => {});
  }
  return s;
}

/** Each part's summary, and the slowest samples whole (where a slow stop's time went). */
export function breakdownSummary(parts: StopBreakdown[], slowest = 5) {
  const keys = ['total', 'input', 'dispatch', 'page', 'queue', 'wire'] as const;
  const r = (v: number) => Math.round(v * 100) / 100;
  return {
    ...Object.fromEntries(keys.map((k) => [k, summarize(parts.map((p) => p[k]))])),
    slowest: [...parts]
      .filter((p) => Number.isFinite(p.total))
      .sort((a, b) => b.total - a.total)
      .slice(0, slowest)
      .map((p) => Object.fromEntries(keys.map((k) => [k, r(p[k])]))),
  };
}
