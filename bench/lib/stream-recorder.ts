/**
 * An arm's status stream as received by the bench process: each stamped state group's `$TIM`
 * and pulses, so a servo's true angle at any instant is the simulator's trajectory, linear
 * between its samples (the simulator moves linearly), and each group's arrival here minus its
 * stamp (the stream's one-way delay to a Node subscriber). Used by the browser and twin sections
 * (bench/browser.ts, bench/twin.ts) through ./recorded-arm.ts.
 */
import { angleFromPwm } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';

export class StreamRecorder {
  readonly stamp: number[] = [];
  readonly pwm: number[] = [];
  /** Arrival (epoch ms) − `$TIM` per recorded group, ms. */
  readonly arrivalMinusStamp: number[] = [];
  private readonly re = /\$TIM:(\d+)!\{((?:#\d{3}P\d{4}!)+)\}/g;
  on = false;

  constructor(private readonly servos: number) {}

  feed(payload: Buffer): void {
    if (!this.on || this.stamp.length > 500_000) return;
    const at = performance.timeOrigin + performance.now();
    const text = payload.toString('latin1');
    for (const m of text.matchAll(this.re)) {
      const t = Number(m[1]);
      const ps = [...m[2]!.matchAll(/#(\d{3})P(\d{4})!/g)];
      if (ps.length !== this.servos) continue;
      this.stamp.push(t);
      for (const p of ps) this.pwm.push(Number(p[2]));
      this.arrivalMinusStamp.push(at - t);
    }
  }

  clear(): void {
    this.stamp.length = 0;
    this.pwm.length = 0;
    this.arrivalMinusStamp.length = 0;
  }

  /** Servo i's angle at epoch ms t, linear between samples; NaN outside the record. */
  angleAt(i: number, t: number): number {
    const s = this.stamp;
    if (!(t >= s[0]! && t <= s[s.length - 1]!)) return NaN;
    let lo = 0;
    let hi = s.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (s[mid]! <= t) lo = mid;
      else hi = mid;
    }
    const n = this.servos;
    const a = this.pwm[lo * n + i]!;
    const b = this.pwm[hi * n + i]!;
    const f = s[hi] === s[lo] ? 0 : (t - s[lo]!) / (s[hi]! - s[lo]!);
    return angleFromPwm(a + (b - a) * f, DEMO_ARM.servos[i]!.polarity);
  }
}
