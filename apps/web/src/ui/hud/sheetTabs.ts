/**
 * The phone and narrow-tablet layout's tab bar (./PanelTabs.tsx): which tab shows which panels in
 * the bottom sheet, one tab open at a time, and what a swipe on the sheet's handle or the tab bar
 * means. Pure: no DOM, no React. On a wide screen every panel is shown and the tab bar is hidden
 * (../app/layout.css).
 */

/** The tabs, in the bar's order: `id` keys the panels' slots, `label` is the button's name. */
export const PANEL_TABS = [
  { id: 'jog', label: 'Jog' },
  { id: 'target', label: 'Target' },
  { id: 'view', label: 'View' },
  { id: 'arm', label: 'Arm' },
  { id: 'setup', label: 'Setup' },
] as const;

export type PanelTab = (typeof PANEL_TABS)[number]['id'];

/** What a tap on tab `tab` does to the sheet showing `open` (null: lowered): raise or lower it. */
export function tapTab(open: PanelTab | null, tab: PanelTab): PanelTab | null {
  return open === tab ? null : tab;
}

export interface SwipeOptions {
  /** How far (CSS px) a finger must travel up or down for a swipe, not a tap. */
  minDistancePx: number;
}

export const DEFAULT_SWIPE_OPTIONS: SwipeOptions = { minDistancePx: 40 };

/**
 * The sheet after a vertical swipe of `dy` px (down is positive) that started on the handle or
 * the tab bar: up raises it on the last tab shown (`last`), down lowers it; a shorter move is
 * no swipe (`undefined`: a tap, handled as one).
 */
export function swipeSheet(
  open: PanelTab | null,
  last: PanelTab,
  dy: number,
  opts: SwipeOptions = DEFAULT_SWIPE_OPTIONS,
): PanelTab | null | undefined {
  if (dy <= -opts.minDistancePx) return open ?? last;
  if (dy >= opts.minDistancePx) return null;
  return undefined;
}
