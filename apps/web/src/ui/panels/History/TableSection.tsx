/**
 * One table of the History panel's tables tab: its heading with the CSV button, the load's error
 * in its place, a line when the range holds nothing, else the table (its column heads and a row
 * per item), and the notes the answer calls for (thinned, truncated).
 */
import type { ReactNode } from 'react';
import type { Loaded } from './loaded.ts';
import { ViewError, ViewHeader } from './ViewHeader.tsx';

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
  row(item: T, index: number): ReactNode;
  /** Notes under the table, from the answer (thinned, truncated). */
  notes?(data: D): ReactNode;
}

export function TableSection<D, T>(p: TableSectionProps<D, T>) {
  const v = p.view;
  const items = v.ok ? p.items(v.data) : [];
  return (
    <section className="history-view" aria-label={p.title}>
      <ViewHeader title={p.title} csvLabel={p.csvLabel} onCsv={v.ok ? () => p.csv(v.data) : null} />
      {!v.ok && <ViewError error={v.error} />}
      {v.ok && items.length === 0 && p.empty}
      {v.ok && items.length > 0 && (
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
          <tbody>{items.map((item, i) => p.row(item, i))}</tbody>
        </table>
      )}
      {v.ok && p.notes?.(v.data)}
    </section>
  );
}
