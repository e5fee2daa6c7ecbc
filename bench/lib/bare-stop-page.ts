/// <reference lib="dom" />
/**
 * The emergency stop's floor in this browser on this machine (issue 17 item 3's baseline): a
 * bare page, in the same browser as the HUD and while the HUD runs, with one button named
 * "Emergency stop" whose `pointerdown` (and the Escape key) sends a `#255PDST!` PUBLISH (QoS 1,
 * as the HUD sends it) on an MQTT connection over one WebSocket, packets written by hand:
 * no framework, no stream, no rendering. The same probe (./estop-probe.ts) measures it; what it
 * takes is what input, the browser, the socket, the broker and the machine's scheduling take.
 */
import type { Browser, Page } from 'playwright-core';

/** Runs in the bare page: connects and arms the button; resolves once the CONNACK came. */
function bareStop(args: { wsUrl: string; topic: string; payload: string }): Promise<void> {
  const bytes = (s: string): number[] => Array.from(new TextEncoder().encode(s));
  const str = (s: string): number[] => {
    const b = bytes(s);
    return [b.length >> 8, b.length & 255, ...b];
  };
  const packet = (head: number, body: number[]): Uint8Array => {
    const len: number[] = [];
    let n = body.length;
    do {
      let d = n % 128;
      n = Math.floor(n / 128);
      if (n > 0) d |= 128;
      len.push(d);
    } while (n > 0);
    return Uint8Array.from([head, ...len, ...body]);
  };
  const ws = new WebSocket(args.wsUrl, 'mqtt');
  ws.binaryType = 'arraybuffer';
  let id = 0;
  const stop = (): void => {
    id = (id % 65535) + 1;
    ws.send(packet(0x32, [...str(args.topic), id >> 8, id & 255, ...bytes(args.payload)]));
  };
  const button = document.createElement('button');
  button.textContent = 'Emergency stop';
  button.style.cssText = 'width:200px;height:80px;margin:40px';
  document.body.append(button);
  button.addEventListener('pointerdown', stop, { capture: true });
  window.addEventListener('keydown', (e) => e.key === 'Escape' && stop(), { capture: true });
  return new Promise((resolve, reject) => {
    ws.onopen = () =>
      ws.send(packet(0x10, [...str('MQTT'), 4, 2, 0, 60, ...str(`bench-bare-${Date.now()}`)]));
    ws.onmessage = (e) => {
      if (new Uint8Array(e.data as ArrayBuffer)[0] === 0x20) resolve();
    };
    ws.onerror = () => reject(new Error('the bare page could not connect'));
  });
}

/** Opens the bare stop page in `browser` (a new context), connected to `wsUrl`. */
export async function openBareStopPage(
  browser: Browser,
  wsUrl: string,
  topic: string,
  payload: string,
): Promise<Page> {
  const context = await browser.newContext({ viewport: { width: 400, height: 300 } });
  // tsx wraps named functions in __name(); the page needs it to exist (as ./hud-browser.ts).
  await context.addInitScript({ content: 'globalThis.__name = (f) => f;' });
  const page = await context.newPage();
  await page.setContent('<!doctype html><title>bare stop</title><body></body>');
  await page.evaluate(bareStop, { wsUrl, topic, payload });
  return page;
}
