/**
 * The health history's row being taken in (./HealthHistory.ts): each servo's temperature and
 * voltage from one report's health frames (NaN for a servo that did not report), pushed with
 * the thermal model's predicted temperatures once the report is read. Allocates nothing after
 * construction.
 */
import type { ThermalWatch } from '@armtwin/thermal';
import type { HealthHistory } from './HealthHistory.ts';

export class HealthRow {
  private readonly temp: Float64Array;
  private readonly volt: Float64Array;
  private readonly predicted: Float64Array;

  constructor(readonly servoCount: number) {
    this.temp = new Float64Array(servoCount);
    this.volt = new Float64Array(servoCount);
    this.predicted = new Float64Array(servoCount);
  }

  /** A new row: no servo reported yet. */
  clear(): void {
    this.temp.fill(NaN);
    this.volt.fill(NaN);
  }

  /** Servo `id` reported `temp` °C and `mv` millivolts. */
  set(id: number, temp: number, mv: number): void {
    this.temp[id] = temp;
    this.volt[id] = mv / 1000;
  }

  /**
   * Feeds each reported temperature to `thermal` and pushes the row, stamped `stamp` (epoch ms;
   * now when the report had no `$TIM`), to `history` with the predicted temperatures.
   */
  push(stamp: number | undefined, thermal: ThermalWatch, history: HealthHistory): void {
    const t = stamp ?? Date.now();
    this.predicted.fill(NaN);
    for (let i = 0; i < this.servoCount; i++) {
      if (Number.isNaN(this.temp[i]!)) continue;
      thermal.health(i, t, this.temp[i]!);
      this.predicted[i] = thermal.state(i)!.predictedC;
    }
    history.push(t / 1000, this.temp, this.volt, this.predicted);
  }
}
