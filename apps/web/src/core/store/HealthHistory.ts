import { RingBuffer } from './RingBuffer.ts';

/**
 * Temperature and voltage history of every servo, for the strip charts: one shared time ring
 * (seconds) and one ring per servo and quantity, all the same fixed length. A row is pushed per
 * health report; a servo missing from a report repeats its last value.
 */
export class HealthHistory {
  readonly time: RingBuffer;
  readonly temp: RingBuffer[];
  readonly volt: RingBuffer[];
  /** The thermal model's predicted temperature per servo (@armtwin/protocol ThermalWatch), °C. */
  readonly predicted: RingBuffer[];
  /** Bumped on every push, so a chart redraws only when there is something new. */
  version = 0;

  constructor(
    readonly servoCount: number,
    readonly capacity: number,
  ) {
    this.time = new RingBuffer(capacity);
    this.temp = Array.from({ length: servoCount }, () => new RingBuffer(capacity));
    this.volt = Array.from({ length: servoCount }, () => new RingBuffer(capacity));
    this.predicted = Array.from({ length: servoCount }, () => new RingBuffer(capacity));
  }

  /**
   * One row at `timeS` (Unix seconds); `temps` °C and `volts` V by servo, NaN = not reported;
   * `predicted` °C by servo, NaN = none (drawn as no line).
   */
  push(
    timeS: number,
    temps: ArrayLike<number>,
    volts: ArrayLike<number>,
    predicted?: ArrayLike<number>,
  ): void {
    this.time.push(timeS);
    for (let i = 0; i < this.servoCount; i++) {
      const t = temps[i] ?? NaN;
      const v = volts[i] ?? NaN;
      this.temp[i]!.push(Number.isNaN(t) ? this.temp[i]!.latest() : t);
      this.volt[i]!.push(Number.isNaN(v) ? this.volt[i]!.latest() : v);
      const p = predicted?.[i] ?? NaN;
      this.predicted[i]!.push(Number.isNaN(p) ? this.predicted[i]!.latest() : p);
    }
    this.version++;
  }

  /**
   * A break in the data (the broker connection dropped): a row of NaN, drawn as a gap (the
   * charts hand uPlot null). Its time is kept after the last row so time stays ordered.
   */
  pushGap(timeS: number): void {
    const last = this.time.latest();
    this.time.push(Number.isNaN(last) ? timeS : Math.max(timeS, last + 0.001));
    for (const r of this.temp) r.push(NaN);
    for (const r of this.volt) r.push(NaN);
    for (const r of this.predicted) r.push(NaN);
    this.version++;
  }

  clear(): void {
    this.time.clear();
    for (const r of this.temp) r.clear();
    for (const r of this.volt) r.clear();
    for (const r of this.predicted) r.clear();
    this.version++;
  }
}
