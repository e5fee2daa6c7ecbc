/**
 * Vertical swipes on an element (the sheet's handle, the tab bar): calls `onSwipe(dy)` when a
 * pointer or finger is lifted after moving, and tells a click that ends a swipe from a tap
 * (`wasSwipe`), so a swipe that ends on a tab does not also toggle it.
 */
import { useRef } from 'react';

export interface Swipe {
  onPointerDown(e: React.PointerEvent): void;
  onPointerUp(e: React.PointerEvent): void;
  onPointerCancel(): void;
  /** True once, for the click that follows a swipe. */
  wasSwipe(): boolean;
}

/** `onSwipe` returns whether it took the move as a swipe (a short move is a tap). */
export function useSwipe(onSwipe: (dy: number) => boolean): Swipe {
  const start = useRef<number | null>(null);
  const swiped = useRef(false);
  return {
    onPointerDown(e) {
      start.current = e.clientY;
      swiped.current = false;
    },
    onPointerUp(e) {
      if (start.current === null) return;
      swiped.current = onSwipe(e.clientY - start.current);
      start.current = null;
    },
    onPointerCancel() {
      start.current = null;
    },
    wasSwipe() {
      const was = swiped.current;
      swiped.current = false;
      return was;
    },
  };
}
