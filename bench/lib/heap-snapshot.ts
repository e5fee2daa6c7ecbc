/**
 * A page's V8 heap by constructor, for the soak (../soak.ts): CDP `HeapProfiler.takeHeapSnapshot`
 * (after a forced GC), the snapshot's nodes summed by kind and name (an object's constructor, a
 * closure's function name, `(string)`, `(array)`, …), then the difference between two summaries:
 * what grew between an early and a late minute is where a leak lives.
 */
import type { CDPSession } from 'playwright-core';

export interface HeapEntry {
  count: number;
  bytes: number;
}
export type HeapSummary = Map<string, HeapEntry>;

interface Snapshot {
  snapshot: { meta: { node_fields: string[]; node_types: [string[], ...unknown[]] } };
  nodes: number[];
  strings: string[];
}

/** Sums a parsed `.heapsnapshot` by node kind and name (self sizes). Pure. */
export function summarizeSnapshot(s: Snapshot): HeapSummary {
  const fields = s.snapshot.meta.node_fields;
  const types = s.snapshot.meta.node_types[0];
  const width = fields.length;
  const iType = fields.indexOf('type');
  const iName = fields.indexOf('name');
  const iSize = fields.indexOf('self_size');
  const out: HeapSummary = new Map();
  for (let k = 0; k < s.nodes.length; k += width) {
    const type = types[s.nodes[k + iType]!] ?? '?';
    const name = s.strings[s.nodes[k + iName]!] ?? '?';
    const key =
      type === 'object' || type === 'native'
        ? name
        : type === 'closure'
          ? `closure ${name || '(anonymous)'}`
          : type === 'hidden' || type === 'array' || type === 'object shape'
            ? `(${type}) ${name}`
            : `(${type})`;
    const e = out.get(key);
    if (e) {
      e.count++;
      e.bytes += s.nodes[k + iSize]!;
    } else out.set(key, { count: 1, bytes: s.nodes[k + iSize]! });
  }
  return out;
}

/** Forces a GC, takes a heap snapshot of the page and summarizes it. */
export async function heapSummary(cdp: CDPSession): Promise<HeapSummary> {
  const chunks: string[] = [];
  const onChunk = (e: { chunk: string }) => chunks.push(e.chunk);
  cdp.on('HeapProfiler.addHeapSnapshotChunk', onChunk);
  try {
    await cdp.send('HeapProfiler.collectGarbage');
    await cdp.send('HeapProfiler.takeHeapSnapshot', { reportProgress: false });
  } finally {
    cdp.off('HeapProfiler.addHeapSnapshotChunk', onChunk);
  }
  return summarizeSnapshot(JSON.parse(chunks.join('')) as Snapshot);
}

export interface HeapGrowth {
  name: string;
  count: number;
  bytes: number;
  countAfter: number;
}

/** The `top` entries that grew most in bytes from `a` to `b` (then by count). Pure. */
export function heapGrowth(a: HeapSummary, b: HeapSummary, top = 15): HeapGrowth[] {
  const rows: HeapGrowth[] = [];
  for (const [name, e] of b) {
    const before = a.get(name) ?? { count: 0, bytes: 0 };
    const d = { name, count: e.count - before.count, bytes: e.bytes - before.bytes };
    if (d.bytes > 0 || d.count > 0) rows.push({ ...d, countAfter: e.count });
  }
  return rows.sort((x, y) => y.bytes - x.bytes || y.count - x.count).slice(0, top);
}
