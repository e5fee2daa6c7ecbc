/**
 * The tab bar of the phone and narrow-tablet layout (hidden on a wide screen, ../app/layout.css): one
 * button per tab of ./sheetTabs.ts raises the bottom sheet on that tab's panels, or lowers it when
 * that tab is already open; a swipe up on the bar raises the sheet, a swipe down lowers it.
 */
import { PANEL_TABS, swipeSheet, tapTab, type PanelTab } from './sheetTabs.ts';
import { useSwipe } from './useSwipe.ts';

interface Props {
  open: PanelTab | null;
  last: PanelTab;
  /** The sheet's element id (the buttons control it). */
  sheetId: string;
  onOpen(tab: PanelTab | null): void;
}

export function PanelTabs({ open, last, sheetId, onOpen }: Props) {
  const swipe = useSwipe((dy) => {
    const next = swipeSheet(open, last, dy);
    if (next === undefined) return false;
    onOpen(next);
    return true;
  });
  return (
    <nav
      className="hud-tabs"
      aria-label="Panels"
      onPointerDown={swipe.onPointerDown}
      onPointerUp={swipe.onPointerUp}
      onPointerCancel={swipe.onPointerCancel}
    >
      {PANEL_TABS.map((t) => (
        <button
          key={t.id}
          type="button"
          className={open === t.id ? 'hud-tab on' : 'hud-tab'}
          aria-expanded={open === t.id}
          aria-controls={sheetId}
          data-testid={`tab-${t.id}`}
          onClick={() => {
            if (!swipe.wasSwipe()) onOpen(tapTab(open, t.id));
          }}
        >
          {t.label}
        </button>
      ))}
    </nav>
  );
}
