/**
 * The servos' motion, heat and supply: plain typed arrays, advanced by an injected time (ms).
 * No I/O, no clock of its own. Motion is linear interpolation from the position at command
 * time to the target, over the commanded time or, when that would be faster than the servo's
 * top speed, over the shortest time the top speed allows.
 */
import { servoLimitsPwm } from '@armtwin/ik';
import { PWM_CENTRE, US_PER_DEG } from '@armtwin/protocol';
import type { SimModelOptions } from './options.ts';

export class Servos {
  readonly count: number;
  readonly ids: Int32Array;
  /** Pulse limits of each servo, µs. */
  readonly minPwm: Float64Array;
  readonly maxPwm: Float64Array;
  /** Top speed, µs per ms. */
  readonly vmax: Float64Array;
  /** The current segment: from `from` at `t0` to `to` over `dur` ms. */
  readonly from: Float64Array;
  readonly to: Float64Array;
  readonly t0: Float64Array;
  readonly dur: Float64Array;
  readonly stalled: Uint8Array;
  /** Overheat target, °C; NaN when off. */
  readonly overheat: Float64Array;
  readonly temp: Float64Array;
  /** Current drawn over the last advance, A. */
  readonly amps: Float64Array;
  /** Voltage at each servo after the last advance, and the lowest since `takeMinMv`. */
  readonly mv: Float64Array;
  readonly minMv: Float64Array;
  /** Supply ceiling from an undervolt fault, mV; NaN when off. */
  supplyLimitMv = NaN;
  private last: number;
  private readonly prev: Float64Array;

  constructor(
    private readonly o: SimModelOptions,
    now: number,
  ) {
    const n = (this.count = o.arm.servos.length);
    this.ids = Int32Array.from(o.arm.servos, (s) => s.id);
    this.minPwm = Float64Array.from(o.arm.servos, (s) => servoLimitsPwm(s).min);
    this.maxPwm = Float64Array.from(o.arm.servos, (s) => servoLimitsPwm(s).max);
    this.vmax = Float64Array.from(o.arm.servos, (s) => (s.maxSpeedDegPerS * US_PER_DEG) / 1000);
    this.from = Float64Array.from({ length: n }, (_, i) => o.initialPwm[i] ?? PWM_CENTRE);
    this.to = Float64Array.from(this.from);
    this.prev = Float64Array.from(this.from);
    this.t0 = new Float64Array(n).fill(now);
    this.dur = new Float64Array(n);
    this.stalled = new Uint8Array(n);
    this.overheat = new Float64Array(n).fill(NaN);
    this.amps = Float64Array.from({ length: n }, (_, i) => o.holdAmps[i] ?? 0);
    // Power on warm: each servo at the steady temperature of holding its pose.
    this.temp = Float64Array.from(this.amps, (a) => o.ambientC + o.degPerAmp * a);
    this.mv = new Float64Array(n);
    this.minMv = new Float64Array(n);
    this.last = now;
    this.updateSupply();
    this.minMv.set(this.mv);
  }

  /** Index of servo `id`, or -1. */
  indexOf(id: number): number {
    for (let i = 0; i < this.count; i++) if (this.ids[i] === id) return i;
    return -1;
  }

  /** Position of servo i at time t, µs (not rounded). */
  pwmAt(i: number, t: number): number {
    const from = this.from[i]!;
    if (this.stalled[i]) return from;
    const dur = this.dur[i]!;
    const e = t - this.t0[i]!;
    if (e >= dur) return this.to[i]!;
    if (e <= 0) return from;
    return from + ((this.to[i]! - from) * e) / dur;
  }

  /** Whether servo i is still on its way at time t (a stalled servo with a target pushes). */
  isMoving(i: number, t: number): boolean {
    if (this.stalled[i]) return this.from[i] !== this.to[i];
    return t < this.t0[i]! + this.dur[i]! && this.from[i] !== this.to[i];
  }

  /**
   * Integrates current, heat and supply from the last call up to t. Call before changing a
   * segment, so that each interval sees one segment only. Times before the last call are ignored.
   */
  advance(t: number): void {
    const dt = t - this.last;
    if (!(dt > 0)) return;
    const o = this.o;
    for (let i = 0; i < this.count; i++) {
      const p = this.pwmAt(i, t);
      const speed = Math.abs(p - this.prev[i]!) / dt / this.vmax[i]!;
      this.prev[i] = p;
      const pushing = this.stalled[i] && this.from[i] !== this.to[i];
      this.amps[i] =
        (o.holdAmps[i] ?? 0) + o.moveAmps * Math.min(1, speed) + (pushing ? o.stallAmps : 0);
      let steady = o.ambientC + o.degPerAmp * this.amps[i]!;
      let tau = o.thermalTauMs;
      const hot = this.overheat[i]!;
      if (hot > steady) {
        steady = hot;
        tau = o.overheatTauMs;
      }
      this.temp[i]! += (steady - this.temp[i]!) * (1 - Math.exp((-dt * o.thermalTimeScale) / tau));
    }
    this.last = t;
    this.updateSupply();
  }

  private updateSupply(): void {
    let total = 0;
    for (let i = 0; i < this.count; i++) total += this.amps[i]!;
    const supply = Number.isNaN(this.supplyLimitMv)
      ? this.o.supplyMv
      : Math.min(this.o.supplyMv, this.supplyLimitMv);
    const bus = supply - 1000 * this.o.supplyOhms * total;
    for (let i = 0; i < this.count; i++) {
      const v = Math.max(0, bus - 1000 * this.o.servoLeadOhms * this.amps[i]!);
      this.mv[i] = v;
      if (v < this.minMv[i]!) this.minMv[i] = v;
    }
  }

  /** Starts a segment for servo i from where it is at t to `pwm`, in `ms` or as fast as allowed. */
  moveTo(i: number, pwm: number, ms: number, t: number): void {
    const p = this.pwmAt(i, t);
    this.from[i] = p;
    this.prev[i] = p;
    this.to[i] = pwm;
    this.t0[i] = t;
    this.dur[i] = Math.max(ms, Math.abs(pwm - p) / this.vmax[i]!);
  }

  /** Stops servo i where it is at t. */
  stop(i: number, t: number): void {
    const p = this.pwmAt(i, t);
    this.from[i] = this.to[i] = this.prev[i] = p;
    this.t0[i] = t;
    this.dur[i] = 0;
  }

  /**
   * Puts servo i at `pwm` at once, at rest (a model copy set to the real arm's pose: a
   * simulation may jump). A stalled servo stays jammed, now at `pwm`.
   */
  place(i: number, pwm: number, t: number): void {
    this.from[i] = this.to[i] = this.prev[i] = pwm;
    this.t0[i] = t;
    this.dur[i] = 0;
  }

  /** Jams servo i at its position at t (it keeps its target and pushes) or frees it. */
  setStalled(i: number, on: boolean, t: number): void {
    if (on === Boolean(this.stalled[i])) return;
    if (on) {
      this.from[i] = this.prev[i] = this.pwmAt(i, t);
      this.stalled[i] = 1;
    } else {
      // Freed: resume from where it was jammed towards its target, at top speed.
      const p = this.from[i]!;
      this.stalled[i] = 0;
      this.t0[i] = t;
      this.dur[i] = Math.abs(this.to[i]! - p) / this.vmax[i]!;
    }
  }

  /** The lowest voltage seen by servo i since the last call, then starts a new window. */
  takeMinMv(i: number): number {
    const v = this.minMv[i]!;
    this.minMv[i] = this.mv[i]!;
    return v;
  }
}
