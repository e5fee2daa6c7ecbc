/**
 * Samples plain (non-React) state a few times a second: the only way store data reaches React.
 * Re-renders only when the sampled value changes (`sampleEqual`: plain objects and arrays
 * compared member by member).
 */
import { useEffect, useRef, useState } from 'react';
import { sampleEqual } from './sampleEqual.ts';

/** How often panels sample the store, ms. */
export const SAMPLE_INTERVAL_MS = 250;

export function useSampled<T>(read: () => T, intervalMs = SAMPLE_INTERVAL_MS): T {
  const readRef = useRef(read);
  useEffect(() => {
    readRef.current = read;
  });
  const [value, setValue] = useState(read);
  useEffect(() => {
    const id = setInterval(() => {
      const next = readRef.current();
      setValue((prev) => (sampleEqual(prev, next) ? prev : next));
    }, intervalMs);
    return () => clearInterval(id);
  }, [intervalMs]);
  return value;
}
