/// <reference lib="dom" />
/**
 * Code that runs inside the HUD page (passed to Playwright's `page.evaluate`), using only the
 * HUD's debug hook `window.__armtwin` ({ store, viewer, … }). Per rendered frame (the viewer's
 * `renderHooks`) it records the wall time (performance.timeOrigin + performance.now(), epoch
 * ms), the newest `$TIM` of a state report taken in (`store.lastStateStamp`), and
 * `store.rendered` (the servo angles drawn). A HUD without those hooks (older builds) is probed
 * by wrapping `store.ingest` (newest `$TIM` of each state payload) and `renderer.render`. The
 * time inside `renderer.render` is always measured by wrapping it. It also counts
 * requestAnimationFrame callbacks and long tasks. Fixed-size typed arrays: bounded memory.
 */

export interface ProbeResult {
  frames: number;
  wall: number[];
  stamp: number[];
  angles: number[];
  rafCount: number;
  rafMaxGapMs: number;
  renderedFramesDelta: number;
  longTasks: { start: number; duration: number }[];
  windowMs: number;
  clockSkewStartMs: number;
  clockSkewEndMs: number;
  chartCanvases: number;
  pixelRatio: number;
  /** A moving frame's cost where the worker budgets software WebGL's frames (else 0), ms. */
  frameCostMs: number;
  storeMessages: number;
  servoCount: number;
  /** Time spent inside renderer.render (WebGL submission, incl. waits on the GPU process). */
  renderMsTotal: number;
  renderMsMax: number;
  /** Whose frames were recorded: the page's renderer, or the render worker's reports. */
  drawnBy: 'main' | 'worker';
}

interface Hook {
  store: {
    ingest(p: string | Uint8Array, now: number): void;
    rendered: Float64Array;
    counters: { messages: number };
    lastStateStamp?: number;
  };
  viewer: {
    renderer: { render(s: unknown, c: unknown): void };
    renderedFrames: number;
    pixelRatio: number;
    frameCostMs?: number;
    renderHooks?: Set<(now: number) => void>;
    thread?: 'main' | 'worker';
    jointValues?(which?: 'robot'): number[];
  };
  robots?: {
    active?: { spec?: { joints?: { scale: ArrayLike<number>; bias: ArrayLike<number> } } };
  };
}
interface Probe {
  start(): void;
  stop(): ProbeResult;
}
type W = Window & { __armtwin?: Hook; __benchProbe?: Probe };

/** Installs the probe (idle until `start()`); call via page.evaluate(installProbe, maxFrames). */
export function installProbe(maxFrames: number): boolean {
  const w = window as W;
  const hook = w.__armtwin;
  if (!hook?.store || !hook.viewer?.renderer) return false;
  const { store, viewer } = hook;
  const n = store.rendered.length;
  const wall = new Float64Array(maxFrames);
  const stamp = new Float64Array(maxFrames);
  const angles = new Float64Array(maxFrames * n);
  const dec = new TextDecoder();
  const position = /#\d{3}P\d{4}!/;
  const epoch = () => performance.timeOrigin + performance.now();
  let newest = NaN;
  let k = 0;
  let on = false;
  let raf = 0;
  let rafLast = NaN;
  let rafMaxGap = 0;
  let t0 = 0;
  let skew0 = 0;
  let frames0 = 0;
  let msgs0 = 0;
  let renderMs = 0;
  let renderMax = 0;
  const longTasks: { start: number; duration: number }[] = [];

  const hooked = 'lastStateStamp' in store && viewer.renderHooks instanceof Set;
  if (!hooked) {
    const ingest = store.ingest.bind(store);
    store.ingest = (payload, now) => {
      ingest(payload, now);
      const text = typeof payload === 'string' ? payload : dec.decode(payload);
      const j = text.lastIndexOf('$TIM:');
      if (j >= 0 && position.test(text.slice(j))) {
        const t = Number(text.slice(j + 5, text.indexOf('!', j)));
        if (!(t <= newest)) newest = t;
      }
    };
  }
  // A frame drawn by the scene runtime (in the render worker or on this thread): its hook runs
  // when the page hears of it (later, and the page may have sampled a newer pose since), with
  // the runtime's draw time and the joint values it drew, as its report says; those are the
  // frame's instant and angles (URDF value = scale·angle + bias).
  const map = hook.robots?.active?.spec?.joints;
  const fromWorker = !!map && !!viewer.jointValues;
  const record = (now?: number) => {
    if (!on || k >= maxFrames) return;
    wall[k] = fromWorker && now !== undefined ? performance.timeOrigin + now : epoch();
    stamp[k] = hooked ? store.lastStateStamp! : newest;
    const drawn = fromWorker ? viewer.jointValues!('robot') : null;
    for (let i = 0; i < n; i++)
      angles[k * n + i] = drawn ? (drawn[i]! - map!.bias[i]!) / map!.scale[i]! : store.rendered[i]!;
    k++;
  };
  if (hooked) viewer.renderHooks!.add(record);
  const renderer = viewer.renderer;
  const render = renderer.render.bind(renderer);
  renderer.render = (scene, camera) => {
    const r0 = performance.now();
    render(scene, camera);
    if (!on) return;
    const dt = performance.now() - r0;
    renderMs += dt;
    if (dt > renderMax) renderMax = dt;
    if (!hooked) record();
  };
  const tick = (t: number) => {
    if (!on) return;
    raf++;
    if (rafLast === rafLast) rafMaxGap = Math.max(rafMaxGap, t - rafLast);
    rafLast = t;
    requestAnimationFrame(tick);
  };
  new PerformanceObserver((list) => {
    if (!on) return;
    for (const e of list.getEntries()) longTasks.push({ start: e.startTime, duration: e.duration });
  }).observe({ type: 'longtask', buffered: false });

  w.__benchProbe = {
    start() {
      on = true;
      k = raf = 0;
      rafLast = NaN;
      rafMaxGap = 0;
      longTasks.length = 0;
      renderMs = renderMax = 0;
      t0 = performance.now();
      skew0 = epoch() - Date.now();
      frames0 = viewer.renderedFrames;
      msgs0 = store.counters.messages;
      requestAnimationFrame(tick);
    },
    stop() {
      on = false;
      return {
        frames: k,
        wall: Array.from(wall.subarray(0, k)),
        stamp: Array.from(stamp.subarray(0, k)),
        angles: Array.from(angles.subarray(0, k * n)),
        rafCount: raf,
        rafMaxGapMs: rafMaxGap,
        renderedFramesDelta: viewer.renderedFrames - frames0,
        longTasks: longTasks.slice(),
        windowMs: performance.now() - t0,
        clockSkewStartMs: skew0,
        clockSkewEndMs: epoch() - Date.now(),
        chartCanvases: document.querySelectorAll('.uplot canvas').length,
        pixelRatio: viewer.pixelRatio,
        frameCostMs: viewer.frameCostMs ?? 0,
        storeMessages: store.counters.messages - msgs0,
        servoCount: n,
        renderMsTotal: renderMs,
        renderMsMax: renderMax,
        drawnBy: fromWorker ? 'worker' : 'main',
      };
    },
  };
  return true;
}

/** A blank page's rAF rate and long tasks over `ms` (the browser's own ceiling). */
export function blankPageFrames(
  ms: number,
): Promise<{ raf: number; windowMs: number; longTasks: number; maxGapMs: number }> {
  return new Promise((resolve) => {
    let raf = 0;
    let last = NaN;
    let maxGap = 0;
    let longTasks = 0;
    new PerformanceObserver((l) => (longTasks += l.getEntries().length)).observe({
      type: 'longtask',
    });
    const t0 = performance.now();
    const tick = (t: number) => {
      raf++;
      if (last === last) maxGap = Math.max(maxGap, t - last);
      last = t;
      if (t - t0 < ms) requestAnimationFrame(tick);
      else resolve({ raf, windowMs: performance.now() - t0, longTasks, maxGapMs: maxGap });
    };
    requestAnimationFrame(tick);
  });
}
