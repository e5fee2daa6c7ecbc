/**
 * Builds status payloads in one reused byte buffer, writing digits directly: the state stream
 * at up to 1000 Hz allocates only the copy it hands to the transport (which may keep it).
 * The output is byte-for-byte what `encodeTime`/`encodePosition`/`encodeAngle`/`encodeHealth`/
 * `encodeGroup` of @armtwin/protocol produce (the unit tests check this).
 */
const HASH = 35;
const BANG = 33;
const LBRACE = 123;
const RBRACE = 125;

export class StatusWriter {
  private buf: Buffer;
  private len = 0;

  constructor(initialBytes = 4096) {
    this.buf = Buffer.allocUnsafe(initialBytes);
  }

  get length(): number {
    return this.len;
  }

  reset(): this {
    this.len = 0;
    return this;
  }

  private ensure(extra: number): void {
    if (this.len + extra <= this.buf.length) return;
    const bigger = Buffer.allocUnsafe(Math.max(this.buf.length * 2, this.len + extra));
    this.buf.copy(bigger, 0, 0, this.len);
    this.buf = bigger;
  }

  private byte(c: number): void {
    this.buf[this.len++] = c;
  }

  /** A non-negative integer, zero-padded to `width` digits (wider if it needs more). */
  private digits(value: number, width: number): void {
    let v = Math.max(0, Math.round(value));
    let n = 1;
    for (let p = 10; p <= v; p *= 10) n++;
    if (n < width) n = width;
    const end = this.len + n;
    for (let k = end - 1; k >= this.len; k--) {
      this.buf[k] = 48 + (v % 10);
      v = Math.floor(v / 10);
    }
    this.len = end;
  }

  /** `$TIM:ms!` */
  time(ms: number): this {
    this.ensure(24);
    this.buf.write('$TIM:', this.len, 'latin1');
    this.len += 5;
    this.digits(ms, 1);
    this.byte(BANG);
    return this;
  }

  groupStart(): this {
    this.ensure(1);
    this.byte(LBRACE);
    return this;
  }

  groupEnd(): this {
    this.ensure(1);
    this.byte(RBRACE);
    return this;
  }

  /** `#IIIPpppp!` */
  position(id: number, pwm: number): this {
    this.ensure(10);
    this.byte(HASH);
    this.digits(id, 3);
    this.byte(80); // P
    this.digits(pwm, 4);
    this.byte(BANG);
    return this;
  }

  /**
   * `#IIIA±ddd.dd!` (PROTOCOL §8): rounded as `encodeAngle` rounds (hundredths, halves away
   * from zero; zero is `+000.00`), held within ±999.99.
   */
  angle(id: number, deg: number): this {
    const h = Math.min(99_999, Math.round(Math.abs(deg) * 100));
    this.ensure(13);
    this.byte(HASH);
    this.digits(id, 3);
    this.byte(65); // A
    this.byte(deg < 0 && h > 0 ? 45 : 43); // - or +
    this.digits(Math.floor(h / 100), 3);
    this.byte(46); // .
    this.digits(h % 100, 2);
    this.byte(BANG);
    return this;
  }

  /** `#IIITtttVvvvv!` */
  health(id: number, temp: number, mv: number): this {
    this.ensure(14);
    this.byte(HASH);
    this.digits(id, 3);
    this.byte(84); // T
    this.digits(Math.min(999, temp), 3);
    this.byte(86); // V
    this.digits(Math.min(9999, mv), 4);
    this.byte(BANG);
    return this;
  }

  /** Already-encoded frames (replies: low rate). */
  text(s: string): this {
    this.ensure(s.length);
    this.len += this.buf.write(s, this.len, 'latin1');
    return this;
  }

  /** A copy of what was written (the transport may hold on to it). */
  take(): Buffer {
    return Buffer.from(this.buf.subarray(0, this.len));
  }
}
