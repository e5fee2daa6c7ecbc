/// <reference lib="dom" />
/**
 * Whether an element is really on screen, as a user sees it: its box lies inside the viewport,
 * and at its centre the topmost element under a finger (`document.elementFromPoint`) is the
 * element itself or something inside it (no panel, sheet or bar drawn over it).
 */
import type { Locator } from '@playwright/test';

export interface OnScreen {
  x: number;
  y: number;
  width: number;
  height: number;
  /** The whole box inside the viewport. */
  inside: boolean;
  /** Nothing drawn over its centre. */
  uncovered: boolean;
  /** What is on top at its centre, for the failure message. */
  onTop: string;
}

export function onScreen(el: Locator): Promise<OnScreen> {
  return el.evaluate((node) => {
    const r = node.getBoundingClientRect();
    const cx = r.left + r.width / 2;
    const cy = r.top + r.height / 2;
    const top = document.elementFromPoint(cx, cy);
    const name = (e: Element | null) =>
      e
        ? `${e.tagName.toLowerCase()}${e.id ? `#${e.id}` : ''}.${Array.from(e.classList).join('.')}`
        : 'nothing';
    return {
      x: r.left,
      y: r.top,
      width: r.width,
      height: r.height,
      inside:
        r.left >= 0 &&
        r.top >= 0 &&
        r.right <= window.innerWidth + 0.5 &&
        r.bottom <= window.innerHeight + 0.5,
      uncovered: top !== null && (top === node || node.contains(top)),
      onTop: name(top),
    };
  });
}
