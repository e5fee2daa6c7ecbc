/**
 * One servo's position as a page following an arm's status sees it (tests/integration): every
 * state report's position of servo `id`, decoded with the protocol reader. Used to check that an
 * operator's jogs reach the arm and that the stop holds it (cluster-nats.test.ts).
 */
import { createReader, type Reader } from '@armtwin/protocol';

export class ReportedPose {
  /** Every reported position of the servo, in order (pwm µs). */
  readonly samples: number[] = [];
  private readonly reader: Reader;

  constructor(readonly id = 0) {
    this.reader = createReader({
      onGroup: (g) => {
        const f = g.frames.find((x) => x.type === 'position' && x.id === id);
        if (g.frames.length >= 6 && f?.type === 'position') this.samples.push(f.pwm);
      },
    });
  }

  /** A status payload of the arm, as received. */
  feed(payload: Buffer): void {
    this.reader.clearStamp();
    this.reader.feed(payload);
  }

  get latest(): number {
    return this.samples.at(-1) ?? NaN;
  }

  /** The latest report is `pwm` (±5). */
  at(pwm: number): boolean {
    return Math.abs(this.latest - pwm) <= 5;
  }

  /** The last `n` reports are one position (±2): the servo holds still. */
  still(n: number): boolean {
    if (this.samples.length < n) return false;
    const last = this.samples.slice(-n);
    return Math.max(...last) - Math.min(...last) <= 2;
  }
}
