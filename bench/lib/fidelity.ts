/**
 * How well the HUD drew the arm (bench/browser.ts, bench/twin.ts): for each frame the page probe
 * recorded (./page-probe.ts), each servo's drawn angle against the simulator's true angle at the
 * frame's wall time (./stream-recorder.ts), beside the ideal "draw the newest sample received"
 * renderer at the same instant, and the display latency (`$TIM` → the frame first showing it).
 */
import type { ProbeResult } from './page-probe.ts';
import type { StreamRecorder } from './stream-recorder.ts';

export interface FrameErrors {
  /** |true − drawn| per frame and servo, degrees. */
  drawn: number[];
  /** |true − newest sample's angle| per frame and servo, degrees. */
  newest: number[];
  /** Wall time − `$TIM` of each frame showing a newer report than the frame before, ms. */
  latency: number[];
}

export function frameErrors(p: ProbeResult, rec: StreamRecorder, servos: number): FrameErrors {
  const n = p.servoCount;
  const out: FrameErrors = { drawn: [], newest: [], latency: [] };
  let prevStamp = NaN;
  for (let k = 0; k < p.frames; k++) {
    const w = p.wall[k]!;
    const s = p.stamp[k]!;
    if (s > prevStamp || (prevStamp !== prevStamp && s === s)) out.latency.push(w - s);
    prevStamp = s;
    for (let i = 0; i < Math.min(n, servos); i++) {
      const truth = rec.angleAt(i, w);
      const shown = p.angles[k * n + i]!;
      if (!Number.isFinite(truth) || !Number.isFinite(shown)) continue;
      out.drawn.push(Math.abs(shown - truth));
      const held = rec.angleAt(i, s);
      if (Number.isFinite(held)) out.newest.push(Math.abs(held - truth));
    }
  }
  return out;
}
