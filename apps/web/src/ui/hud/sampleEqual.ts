/**
 * Whether a panel's new sample equals the one it shows (`useSampled` re-renders only when not).
 * Samples are small plain data built afresh each time — objects, arrays, arrays of objects (the
 * Health panel's rows) — so plain objects and arrays are compared member by member, nested ones
 * too. Anything else (a Map, a class instance, a typed array) is compared by identity: its
 * insides are not the sample's to judge. NaN equals NaN.
 */

/** Nesting deeper than this is compared by identity (samples are two or three levels deep). */
const MAX_DEPTH = 8;

function isPlain(v: unknown): v is Record<string, unknown> | unknown[] {
  if (typeof v !== 'object' || v === null) return false;
  if (Array.isArray(v)) return true;
  const proto: unknown = Object.getPrototypeOf(v);
  return proto === Object.prototype || proto === null;
}

export function sampleEqual(a: unknown, b: unknown, depth = 0): boolean {
  if (Object.is(a, b)) return true;
  if (depth >= MAX_DEPTH || !isPlain(a) || !isPlain(b)) return false;
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  const ka = Object.keys(a);
  if (ka.length !== Object.keys(b).length) return false;
  for (const k of ka) {
    if (!Object.hasOwn(b, k)) return false;
    const va = (a as Record<string, unknown>)[k];
    const vb = (b as Record<string, unknown>)[k];
    if (!sampleEqual(va, vb, depth + 1)) return false;
  }
  return true;
}
