/**
 * The sampling side of `useSampled`: hands a fresh sample on only when it differs from the last
 * one handed on. The comparison is made here, before React sees anything, and not in a
 * `setState(prev => …)` updater: an updater that returns the previous state still leaves an
 * update on the hook's queue (React's eager bail-out keeps it there until the component next
 * renders; facebook/react#21692), and a panel whose value never changes never renders, so at
 * four samples a second per panel those updates pile up without end (issue 17 item 6: the JS
 * heap grew ≈ 0.3 MiB a minute). Pure: no React, no timers.
 */
import { sampleEqual } from './sampleEqual.ts';

/** Returns `offer(next)`: calls `set(next)` when `next` differs from the last value passed on. */
export function changedOnly<T>(
  first: T,
  set: (value: T) => void,
  equal: (a: T, b: T) => boolean = sampleEqual,
): (next: T) => void {
  let last = first;
  return (next) => {
    if (equal(last, next)) return;
    last = next;
    set(next);
  };
}
