/**
 * One table of the History panel's tables tab: its heading with the CSV button, the load's error
 * in its place, a line when the range holds nothing, else the table (its column heads and a row
 * per item, in a scroll box of its own), and the notes the answer calls for (thinned,
 * truncated). A table with row times is on the replay's time axis: the row at the replay's
 * instant is marked (`aria-current="time"`) and kept in view inside the table's box.
 */
import { useEffect, useMemo, useRef, type ReactNode } from 'react';
import { keepRowInView } from './keepInView.ts';
import type { Loaded } from './loaded.ts';
import type { ReplayAt } from './historyChart.ts';
import { useReplayRow } from './replayRow.ts';
import { ViewError, ViewHeader } from './ViewHeader.tsx';

const NO_TIMES: readonly (number | null)[] = [];

export interface TableSectionProps<D, T> {
  /** The heading, also the section's accessible name. */
  title: string;
  csvLabel: string;
  view: Loaded<D>;
  /** Downloads the answer as CSV. */
  csv(data: D): void;
  items(data: D): readonly T[];
  /** What stands in place of an empty table (a line; it may carry the table's test id). */
  empty: ReactNode;
  /** The table's `data-testid`. */
  testId: string;
  columns: readonly string[];
  /** The item's `<tr>`; `current`: it is the row at the replay's instant (mark it). */
  row(item: T, index: number, current: boolean): ReactNode;
  /** Each item's time (epoch ms; null: none), in `items` order: the table is on the replay's axis. */
  times?(data: D): readonly (number | null)[];
  /** The replay's instant on this table's axis (null: none). */
  replayAt?: ReplayAt;
  /** Notes under the table, from the answer (thinned, truncated). */
  notes?(data: D): ReactNode;
}

export function TableSection<D, T>(p: TableSectionProps<D, T>) {
  const v = p.view;
  const items = v.ok ? p.items(v.data) : [];
  const { times } = p;
  const rowTimes = useMemo(() => (v.ok && times ? times(v.data) : NO_TIMES), [v, times]);
  const current = useReplayRow(rowTimes, p.replayAt ?? null);
  const box = useRef<HTMLDivElement>(null);
  useEffect(() => {
    const row = box.current?.querySelector('tbody')?.rows[current];
    if (box.current && row) keepRowInView(box.current, row);
  }, [current, v]);
  return (
    <section className="history-view" aria-label={p.title}>
      <ViewHeader title={p.title} csvLabel={p.csvLabel} onCsv={v.ok ? () => p.csv(v.data) : null} />
      {!v.ok && <ViewError error={v.error} />}
      {v.ok && items.length === 0 && p.empty}
      {v.ok && items.length > 0 && (
        <div className="history-table-box" ref={box}>
          <table className="history-table" data-testid={p.testId}>
            <thead>
              <tr>
                {p.columns.map((c) => (
                  <th key={c} scope="col">
                    {c}
                  </th>
                ))}
              </tr>
            </thead>
            <tbody>{items.map((item, i) => p.row(item, i, i === current))}</tbody>
          </table>
        </div>
      )}
      {v.ok && p.notes?.(v.data)}
    </section>
  );
}
