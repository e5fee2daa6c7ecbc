/** A fixed-capacity ring of numbers: push overwrites the oldest; nothing allocates after construction. */
export class RingBuffer {
  private readonly data: Float64Array;
  private head = 0; // next write index
  private count = 0;

  constructor(readonly capacity: number) {
    if (!Number.isInteger(capacity) || capacity < 1) throw new RangeError(`capacity ${capacity}`);
    this.data = new Float64Array(capacity);
  }

  get length(): number {
    return this.count;
  }

  push(value: number): void {
    this.data[this.head] = value;
    this.head = (this.head + 1) % this.capacity;
    if (this.count < this.capacity) this.count++;
  }

  /** The i-th value, oldest first (0 … length − 1); NaN outside. */
  at(i: number): number {
    if (i < 0 || i >= this.count) return NaN;
    return this.data[(this.head - this.count + i + this.capacity) % this.capacity]!;
  }

  /** The newest value, NaN when empty. */
  latest(): number {
    return this.at(this.count - 1);
  }

  /** Copies the values oldest first into `out` (from index 0) and returns how many. */
  copyInto(out: { [i: number]: number; length: number }): number {
    const n = Math.min(this.count, out.length);
    const skip = this.count - n;
    for (let i = 0; i < n; i++) out[i] = this.at(skip + i);
    return n;
  }

  clear(): void {
    this.head = this.count = 0;
  }
}
