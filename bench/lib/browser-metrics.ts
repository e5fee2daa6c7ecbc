/**
 * What Chromium says about the page: its own counters through CDP (`Performance.getMetrics`, the
 * domain enabled by ./hud-browser.ts: main-thread time in tasks, script, layout and style
 * recalculation, seconds since the page opened; two readings apart give the busy share of the
 * time between them) and the WebGL renderer the page gets.
 */
import type { CDPSession, Page } from 'playwright-core';

export interface CdpMetrics {
  task: number;
  script: number;
  layout: number;
  style: number;
  /** When read: this process's performance.now(), ms. */
  at: number;
}

export async function cdpMetrics(cdp: CDPSession): Promise<CdpMetrics> {
  const { metrics } = (await cdp.send('Performance.getMetrics')) as {
    metrics: { name: string; value: number }[];
  };
  const get = (k: string) => metrics.find((m) => m.name === k)?.value ?? NaN;
  return {
    task: get('TaskDuration'),
    script: get('ScriptDuration'),
    layout: get('LayoutDuration'),
    style: get('RecalcStyleDuration'),
    at: performance.now(),
  };
}

/** The WebGL renderer the page gets (the unmasked name where the browser tells it). */
export function webglRendererName(page: Page): Promise<string> {
  return page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl');
    const ext = gl?.getExtension('WEBGL_debug_renderer_info');
    const name = gl
      ? String(gl.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : gl.RENDERER))
      : 'no WebGL';
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
    return name;
  });
}
