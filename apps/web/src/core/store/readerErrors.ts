/**
 * How every protocol reader on the page counts what it drops (the arm's status stream in the
 * store, the other arms' health reports in the fleet link): in all, by kind, and the first
 * message of each kind. The Status panel shows them.
 */
import { emptyErrorCounts, type ReaderError, type ReaderErrorKind } from '@armtwin/protocol';

export interface DropCounters {
  /** Pieces of input the reader dropped, in all and by kind. */
  dropped: number;
  droppedByKind: Record<ReaderErrorKind, number>;
}

export type FirstErrors = Partial<Record<ReaderErrorKind, string>>;

export const emptyDropCounters = (): DropCounters => ({
  dropped: 0,
  droppedByKind: emptyErrorCounts(),
});

/** Counts one reader error; the first of its kind is kept as text. */
export function countDrop(counters: DropCounters, first: FirstErrors, e: ReaderError): void {
  counters.dropped++;
  counters.droppedByKind[e.kind]++;
  first[e.kind] ??= `${e.message}: ${JSON.stringify(e.text)}`;
}

/** `junk 2, malformed 1`: the kinds seen, with their counts ('' when none). */
export const droppedWords = (byKind: Record<ReaderErrorKind, number>): string =>
  Object.entries(byKind)
    .filter(([, n]) => n > 0)
    .map(([k, n]) => `${k} ${n}`)
    .join(', ');
