/**
 * A growable byte queue for the stream parsers: bytes are appended at the end and taken from the
 * front; it compacts itself, so it never holds more than what is pending plus one chunk.
 * Browser-safe (Uint8Array only). The parsers bound it; it does not bound itself.
 */
export class ByteBuffer {
  private buf = new Uint8Array(0);
  private start = 0;
  private end = 0;

  get length(): number {
    return this.end - this.start;
  }

  append(chunk: Uint8Array): void {
    if (chunk.length === 0) return;
    if (this.end + chunk.length > this.buf.length) {
      const pending = this.length;
      if (pending + chunk.length <= this.buf.length && this.start > 0) {
        this.buf.copyWithin(0, this.start, this.end);
      } else {
        const next = new Uint8Array(Math.max(pending + chunk.length, this.buf.length * 2, 4096));
        next.set(this.buf.subarray(this.start, this.end));
        this.buf = next;
      }
      this.start = 0;
      this.end = pending;
    }
    this.buf.set(chunk, this.end);
    this.end += chunk.length;
  }

  /** The byte at `i` from the front (undefined past the end). */
  at(i: number): number | undefined {
    return i < this.length ? this.buf[this.start + i] : undefined;
  }

  /** A view of the pending bytes; valid until the next append. */
  view(from = 0, to = this.length): Uint8Array {
    return this.buf.subarray(this.start + from, this.start + Math.min(to, this.length));
  }

  /** Position of `pattern` at or after `from`, or -1. */
  indexOf(pattern: Uint8Array, from = 0): number {
    const first = pattern[0]!;
    const last = this.end - pattern.length;
    for (let i = this.start + from; i <= last; i++) {
      i = this.buf.indexOf(first, i);
      if (i < 0 || i > last) return -1;
      let k = 1;
      while (k < pattern.length && this.buf[i + k] === pattern[k]) k++;
      if (k === pattern.length) return i - this.start;
    }
    return -1;
  }

  /** Removes and returns (a copy of) the first `n` bytes. */
  take(n: number): Uint8Array {
    const out = this.buf.slice(this.start, this.start + n);
    this.drop(n);
    return out;
  }

  drop(n: number): void {
    this.start = Math.min(this.start + n, this.end);
    if (this.start === this.end) this.start = this.end = 0;
  }

  clear(): void {
    this.start = this.end = 0;
    if (this.buf.length > 1 << 20) this.buf = new Uint8Array(0);
  }
}
