/**
 * Byte helpers shared by both buses: little-endian words, the sign encodings the two vendors
 * use, and hex for messages and test vectors.
 */

/** Reads an unsigned little-endian value of 1, 2 or 4 bytes. */
export function readUnsigned(bytes: Uint8Array, offset: number, size: 1 | 2 | 4): number {
  let value = 0;
  for (let i = size - 1; i >= 0; i--) value = value * 256 + (bytes[offset + i] ?? 0);
  return value;
}

/** Writes the low `size` bytes of `value` little-endian (two's complement for negatives). */
export function writeUnsigned(
  bytes: Uint8Array,
  offset: number,
  size: 1 | 2 | 4,
  value: number,
): void {
  let v = value < 0 ? value + 2 ** (8 * size) : value;
  for (let i = 0; i < size; i++) {
    bytes[offset + i] = v & 0xff;
    v = Math.floor(v / 256);
  }
}

/** Little-endian bytes of `value` (two's complement for negatives). */
export function le(value: number, size: 1 | 2 | 4): Uint8Array {
  const out = new Uint8Array(size);
  writeUnsigned(out, 0, size, value);
  return out;
}

/** Two's complement: the unsigned `raw` of `size` bytes read as a signed number (Dynamixel). */
export function toSigned(raw: number, size: 1 | 2 | 4): number {
  const half = 2 ** (8 * size - 1);
  return raw >= half ? raw - 2 * half : raw;
}

/**
 * Feetech's sign-magnitude: bit `signBit` set means negative, the bits below it hold the
 * magnitude (the SDK's `SCS_TOHOST(a, b)`). Goal and present position and speed use bit 15,
 * present load bit 10, the homing offset bit 11.
 */
export function fromSignMagnitude(raw: number, signBit: number): number {
  const sign = 2 ** signBit;
  return raw & sign ? -(raw & (sign - 1)) : raw & (sign - 1);
}

/** The inverse of `fromSignMagnitude` (the SDK's `SCS_TOSCS(a, b)`); |value| must be below 2^signBit. */
export function toSignMagnitude(value: number, signBit: number): number {
  return value < 0 ? -value | (2 ** signBit) : value;
}

/** Largest magnitude a sign-magnitude field with this sign bit can carry. */
export const signMagnitudeMax = (signBit: number): number => 2 ** signBit - 1;

/** `FF FF FD 00` → bytes; spaces optional. Throws on odd or non-hex input. */
export function fromHex(text: string): Uint8Array {
  const clean = text.replace(/\s+/g, '');
  if (clean.length % 2 !== 0 || /[^0-9a-f]/i.test(clean)) throw new Error(`not hex: "${text}"`);
  const out = new Uint8Array(clean.length / 2);
  for (let i = 0; i < out.length; i++) out[i] = parseInt(clean.slice(2 * i, 2 * i + 2), 16);
  return out;
}

/** Bytes → `FF FF FD 00` (upper case, space separated). */
export function toHex(bytes: Uint8Array | readonly number[]): string {
  return Array.from(bytes, (b) => b.toString(16).toUpperCase().padStart(2, '0')).join(' ');
}

/** One buffer holding `a` then `b`. */
export function concatBytes(a: Uint8Array, b: Uint8Array): Uint8Array {
  if (a.length === 0) return b;
  if (b.length === 0) return a;
  const out = new Uint8Array(a.length + b.length);
  out.set(a, 0);
  out.set(b, a.length);
  return out;
}
