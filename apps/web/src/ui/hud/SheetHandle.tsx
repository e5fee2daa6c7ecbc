/**
 * The bottom sheet's grab handle (phone and narrow-tablet layout only, ../app/layout.css): a tap or a
 * swipe down lowers the sheet, giving the 3D view the screen; a swipe up keeps it raised.
 */
import { swipeSheet, type PanelTab } from './sheetTabs.ts';
import { useSwipe } from './useSwipe.ts';

interface Props {
  open: PanelTab | null;
  sheetId: string;
  onOpen(tab: PanelTab | null): void;
}

export function SheetHandle({ open, sheetId, onOpen }: Props) {
  const swipe = useSwipe((dy) => {
    if (open === null) return false;
    const next = swipeSheet(open, open, dy);
    if (next === undefined) return false;
    onOpen(next);
    return true;
  });
  return (
    <button
      type="button"
      className="sheet-handle"
      aria-label="Lower the panels"
      aria-controls={sheetId}
      data-testid="sheet-handle"
      onPointerDown={swipe.onPointerDown}
      onPointerUp={swipe.onPointerUp}
      onPointerCancel={swipe.onPointerCancel}
      onClick={() => {
        if (!swipe.wasSwipe()) onOpen(null);
      }}
    />
  );
}
