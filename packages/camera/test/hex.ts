/** Test helpers: hex ↔ bytes, and a stream cut in two at an offset. */
export const fromHex = (hex: string): Uint8Array =>
  Uint8Array.from(hex.match(/../g) ?? [], (b) => parseInt(b, 16));

export const toHex = (bytes: Uint8Array): string =>
  [...bytes].map((b) => b.toString(16).toUpperCase().padStart(2, '0')).join('');

export const concat = (parts: readonly Uint8Array[]): Uint8Array => {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
};

/** Every way to feed `whole`: as given, cut in two at each offset, one byte at a time. */
export function* feedings(chunks: readonly Uint8Array[]): Generator<[string, Uint8Array[]]> {
  yield ['as given', [...chunks]];
  const whole = concat(chunks);
  for (let cut = 0; cut <= whole.length; cut++)
    yield [`cut at ${cut}`, [whole.subarray(0, cut), whole.subarray(cut)]];
  yield ['byte by byte', [...whole].map((b) => Uint8Array.of(b))];
}
