/**
 * The emergency stop measured from outside the page (issue 17 item 3): Playwright's mouse and
 * keyboard through CDP on the HUD's "Emergency stop" button and the Escape key, and a Node
 * MQTT subscriber on the arm's control topic. One sample: the time from dispatching the first
 * input of the gesture (the mouse button's press, released at once after it, as Playwright's
 * `click` does; the Escape key's press) to `#255PDST!` arriving at the subscriber, both read on
 * this process's clock. Whatever renders the page (main thread or a worker) and whichever
 * event the page stops on (`pointerdown` or `click`), the probe sees only input and the wire.
 * Between samples the arm is set moving again (the caller's `rearm`, a move on the control
 * topic) and a random 200–500 ms pause puts the next input at another phase of the page's frame.
 */
import type { MqttClient } from 'mqtt';
import type { Page } from 'playwright-core';
import { connectMqtt } from './stack.ts';
import { sleep } from './proc.ts';

export const STOP_FRAME = '#255PDST!';

export type StopInput = 'click' | 'escape' | 'node';

export interface StopProbe {
  /** `n` samples of input → `#255PDST!` at the subscriber, ms (NaN for a stop that never came). */
  measure(input: StopInput, n: number, rearm: () => Promise<void>): Promise<number[]>;
  close(): Promise<void>;
}

export async function startStopProbe(
  brokerUrl: string,
  arm: string,
  page: Page,
  publisher: MqttClient,
): Promise<StopProbe> {
  const topic = `arm/${arm}/control`;
  const sub = await connectMqtt(brokerUrl, `bench-estop-sub-${process.pid}`);
  let waiting: ((t: number) => void) | null = null;
  sub.on('message', (_t, payload) => {
    const at = performance.now();
    if (waiting && payload.includes(STOP_FRAME)) {
      const w = waiting;
      waiting = null;
      w(at);
    }
  });
  await sub.subscribeAsync(topic, { qos: 0 });

  const button = page.getByRole('button', { name: 'Emergency stop' });
  return {
    async measure(input, n, rearm) {
      const out: number[] = [];
      for (let i = 0; i < n; i++) {
        await rearm();
        await sleep(200 + Math.random() * 300);
        let timer: ReturnType<typeof setTimeout> | undefined;
        const arrived = new Promise<number>((resolve) => {
          waiting = resolve;
          timer = setTimeout(() => resolve(NaN), 3000);
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
      }
      return out;
    },
    async close() {
      await sub.endAsync().catch(() => {});
    },
  };
}
