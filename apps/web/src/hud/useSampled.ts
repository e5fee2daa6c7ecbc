/**
 * Samples plain (non-React) state a few times a second: the only way store data reaches React.
 * Re-renders only when the sampled value changes (shallow comparison of objects and arrays).
 */
import { useEffect, useRef, useState } from 'react';

/** How often panels sample the store, ms. */
export const SAMPLE_INTERVAL_MS = 250;

export function shallowEqual(a: unknown, b: unknown): boolean {
  if (Object.is(a, b)) return true;
  if (typeof a !== 'object' || typeof b !== 'object' || a === null || b === null) return false;
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  const ka = Object.keys(a);
  const kb = Object.keys(b);
  if (ka.length !== kb.length) return false;
  for (const k of ka) {
    const va = (a as Record<string, unknown>)[k];
    const vb = (b as Record<string, unknown>)[k];
    if (!Object.is(va, vb) && !(Array.isArray(va) && Array.isArray(vb) && shallowEqual(va, vb)))
      return false;
  }
  return true;
}

export function useSampled<T>(read: () => T, intervalMs = SAMPLE_INTERVAL_MS): T {
  const readRef = useRef(read);
  useEffect(() => {
    readRef.current = read;
  });
  const [value, setValue] = useState(read);
  useEffect(() => {
    const id = setInterval(() => {
      const next = readRef.current();
      setValue((prev) => (shallowEqual(prev, next) ? prev : next));
    }, intervalMs);
    return () => clearInterval(id);
  }, [intervalMs]);
  return value;
}
