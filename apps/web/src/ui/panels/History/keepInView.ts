/**
 * Keeps a table's marked row visible inside the table's own scroll box, never by scrolling the
 * page or the panel (`scrollIntoView` would move every scrolled ancestor) and never by moving
 * focus. The arithmetic is pure (`scrollTopShowing`); `keepRowInView` applies it.
 */

/** A vertical extent in the box's scrolled content, px. */
export interface Extent {
  top: number;
  height: number;
}

/**
 * The box's scrollTop that shows `row` (its offset in the box's content), or null when the
 * box already shows it whole. A row above the view comes to the top, one below to the bottom;
 * a row taller than the box shows its top.
 */
export function scrollTopShowing(
  scrollTop: number,
  viewHeight: number,
  row: Extent,
): number | null {
  const bottom = row.top + row.height;
  if (row.top >= scrollTop && bottom <= scrollTop + viewHeight) return null;
  if (row.top < scrollTop || row.height >= viewHeight) return row.top;
  return bottom - viewHeight;
}

/** Scrolls `box` (a scroll container holding `row`) just enough to show `row`. */
export function keepRowInView(box: HTMLElement, row: HTMLElement): void {
  const b = box.getBoundingClientRect();
  const r = row.getBoundingClientRect();
  // The row's offset in the box's content, under the sticky header the box may keep on top.
  const head = box.querySelector('thead')?.getBoundingClientRect().height ?? 0;
  const top = r.top - b.top + box.scrollTop - head;
  const next = scrollTopShowing(box.scrollTop, box.clientHeight - head, { top, height: r.height });
  if (next !== null) box.scrollTop = Math.max(0, next);
}
