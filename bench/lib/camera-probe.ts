/// <reference lib="dom" />
/**
 * Code that runs inside the HUD page (passed to Playwright's `page.evaluate`): glass-to-glass
 * latency of the camera views, read from the pixels the page displays.
 *
 * What "shown" means here: each camera view (`section[aria-label="Camera <label>"]`) displays a
 * `<canvas>` that its player draws into outside requestAnimationFrame (on JPEG decode or on
 * WebCodecs output). The probe's own rAF callback reads that canvas: whatever it holds then is
 * what this frame's paint composites, because nothing draws into it between the rAF callbacks
 * and the paint of the same rendering update. In that callback the probe takes `Date.now()`
 * (the same wall clock ffmpeg's `RTCTIME` stamped into the stripe, same machine), reads only the
 * stripe's band of the canvas (`getImageData` of `blockH` rows), decodes it with the camera
 * package's `readTimeStripe` (exposed by the HUD's debug hook, `__armtwin.timeStripe`), and, the
 * first time a frame's stamp is seen, records `now − stamp`. So a figure covers ffmpeg's
 * encode, the server, loopback, the page's decode and draw, and the wait for the next page
 * frame; it stops at the start of the page frame that shows the picture, and does not include
 * the compositor's and a real display's scan-out (headless Chromium has no glass).
 * The time the probe spends reading pixels is measured and reported (`readerMs`), so its own
 * cost is visible in the main-thread busy share. Fixed-size typed arrays: bounded memory.
 */

export interface CameraProbeCamera {
  label: string;
  /** now − stamp (ms) of each frame at the first page frame that showed it. */
  latency: number[];
  /**
   * now − stamp (ms) of the picture shown at every page frame (a held or frozen picture keeps
   * ageing): what the operator sees, where `latency` only counts frames that made it.
   */
  age: number[];
  /** Page frames whose canvas had no readable stripe (not yet drawn, or mangled). */
  unreadable: number;
  /** Page frames where the view or its canvas was missing or not 640×480-like. */
  missing: number;
  /** Distinct frames seen, and stamps that went backwards (a reconnect's replay). */
  distinct: number;
  backwards: number;
  /** The view's age/dropped line at stop (the player's own counters, as the HUD shows them). */
  ageLine: string;
}

export interface CameraProbeResult {
  windowMs: number;
  rafCount: number;
  rafMaxGapMs: number;
  renderedFramesDelta: number;
  longTasks: { start: number; duration: number }[];
  /** Time inside the probe's pixel reading (getImageData + decode), total and worst frame. */
  readerMsTotal: number;
  readerMsMax: number;
  cameras: CameraProbeCamera[];
}

interface Hook {
  viewer: { renderedFrames: number };
  timeStripe: {
    read(px: Uint8ClampedArray, w: number, h: number, stride: number): number | null;
    layout(w: number, h: number): { y0: number; blockH: number };
  };
}
type W = Window & {
  __armtwin?: Hook;
  __cameraProbe?: { start(labels: string[]): void; stop(): CameraProbeResult };
};

/** Installs the probe (idle until `start(labels)`); `page.evaluate(installCameraProbe, args)`. */
export function installCameraProbe(args: {
  width: number;
  height: number;
  maxSamples: number;
}): boolean {
  const w = window as W;
  const hook = w.__armtwin;
  if (!hook?.timeStripe || !hook.viewer) return false;
  const { width, height, maxSamples } = args;
  const { read, layout } = hook.timeStripe;
  const band = layout(width, height);
  // One frame-sized RGBA buffer, allocated once: the band is copied into its rows so that the
  // reader sees the stripe where it expects it; the other rows are never looked at.
  const full = new Uint8ClampedArray(width * height * 4);
  const bandOffset = band.y0 * width * 4;

  interface Cam {
    label: string;
    el: HTMLCanvasElement | null;
    lat: Float64Array;
    n: number;
    age: Float64Array;
    nAge: number;
    last: number;
    unreadable: number;
    missing: number;
    distinct: number;
    backwards: number;
  }
  let cams: Cam[] = [];
  let on = false;
  let raf = 0;
  let rafLast = NaN;
  let rafMaxGap = 0;
  let t0 = 0;
  let frames0 = 0;
  let readerMs = 0;
  let readerMax = 0;
  const longTasks: { start: number; duration: number }[] = [];
  const view = (label: string) =>
    document.querySelector<HTMLElement>(`section[aria-label="${CSS.escape(`Camera ${label}`)}"]`);

  const tick = (t: number) => {
    if (!on) return;
    raf++;
    if (rafLast === rafLast) rafMaxGap = Math.max(rafMaxGap, t - rafLast);
    rafLast = t;
    const now = Date.now();
    const r0 = performance.now();
    for (const c of cams) {
      if (!c.el?.isConnected) c.el = view(c.label)?.querySelector('canvas') ?? null;
      const ctx = c.el?.getContext('2d');
      if (!c.el || !ctx || c.el.width !== width || c.el.height !== height) {
        c.missing++;
        continue;
      }
      full.set(ctx.getImageData(0, band.y0, width, band.blockH).data, bandOffset);
      const stamp = read(full, width, height, 4);
      if (stamp !== null && c.nAge < maxSamples) c.age[c.nAge++] = now - stamp;
      if (stamp === null) c.unreadable++;
      else if (stamp !== c.last) {
        if (stamp > c.last || c.last !== c.last) {
          if (c.n < maxSamples) c.lat[c.n++] = now - stamp;
          c.distinct++;
        } else c.backwards++;
        c.last = stamp;
      }
    }
    const dt = performance.now() - r0;
    readerMs += dt;
    if (dt > readerMax) readerMax = dt;
    requestAnimationFrame(tick);
  };
  new PerformanceObserver((list) => {
    if (!on) return;
    for (const e of list.getEntries()) longTasks.push({ start: e.startTime, duration: e.duration });
  }).observe({ type: 'longtask', buffered: false });

  w.__cameraProbe = {
    start(labels) {
      cams = labels.map((label) => ({
        label,
        el: null,
        lat: new Float64Array(maxSamples),
        n: 0,
        age: new Float64Array(maxSamples),
        nAge: 0,
        last: NaN,
        unreadable: 0,
        missing: 0,
        distinct: 0,
        backwards: 0,
      }));
      on = true;
      raf = 0;
      rafLast = NaN;
      rafMaxGap = readerMs = readerMax = 0;
      longTasks.length = 0;
      t0 = performance.now();
      frames0 = hook.viewer.renderedFrames;
      requestAnimationFrame(tick);
    },
    stop() {
      on = false;
      return {
        windowMs: performance.now() - t0,
        rafCount: raf,
        rafMaxGapMs: rafMaxGap,
        renderedFramesDelta: hook.viewer.renderedFrames - frames0,
        longTasks: longTasks.slice(),
        readerMsTotal: readerMs,
        readerMsMax: readerMax,
        cameras: cams.map((c) => ({
          label: c.label,
          latency: Array.from(c.lat.subarray(0, c.n)),
          age: Array.from(c.age.subarray(0, c.nAge)),
          unreadable: c.unreadable,
          missing: c.missing,
          distinct: c.distinct,
          backwards: c.backwards,
          ageLine: view(c.label)?.querySelector('[data-testid="camera-age"]')?.textContent ?? '',
        })),
      };
    },
  };
  return true;
}
