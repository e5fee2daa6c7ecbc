/**
 * Samples plain (non-React) state a few times a second: the only way store data reaches React.
 * Re-renders only when the sampled value changes (`sampleEqual`: plain objects and arrays
 * compared member by member); an unchanged sample costs React nothing (./changedOnly.ts).
 */
import { useEffect, useRef, useState } from 'react';
import { changedOnly } from './changedOnly.ts';

/** How often panels sample the store, ms. */
export const SAMPLE_INTERVAL_MS = 250;

export function useSampled<T>(read: () => T, intervalMs = SAMPLE_INTERVAL_MS): T {
  const readRef = useRef(read);
  useEffect(() => {
    readRef.current = read;
  });
  const [value, setValue] = useState(read);
  // The last value handed to React. An unchanged sample must not reach setValue at all: see
  // ./changedOnly.ts (a bailed-out update stays queued on a panel that never re-renders).
  const shown = useRef(value);
  useEffect(() => {
    const offer = changedOnly(shown.current, (next: T) => {
      shown.current = next;
      setValue(() => next);
    });
    const id = setInterval(() => offer(readRef.current()), intervalMs);
    return () => clearInterval(id);
  }, [intervalMs]);
  return value;
}
