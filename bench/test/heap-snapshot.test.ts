import { describe, expect, it } from 'vitest';
import { heapGrowth, summarizeSnapshot } from '../lib/heap-snapshot.ts';

/** A minimal V8 heap snapshot: nodes of [type, name, id, self_size, edge_count]. */
function snapshot(nodes: [type: number, name: string, size: number][]) {
  const strings: string[] = [];
  const at = (s: string) => (strings.includes(s) ? strings.indexOf(s) : strings.push(s) - 1);
  return {
    snapshot: {
      meta: {
        node_fields: ['type', 'name', 'id', 'self_size', 'edge_count'],
        node_types: [['hidden', 'array', 'string', 'object', 'code', 'closure'] as string[]] as [
          string[],
        ],
      },
    },
    nodes: nodes.flatMap(([t, n, size], i) => [t, at(n), i + 1, size, 0]),
    strings,
  };
}
const OBJECT = 3;
const CLOSURE = 5;
const STRING = 2;

describe('summarizeSnapshot', () => {
  it('sums objects by constructor, closures by function name, strings together', () => {
    const s = summarizeSnapshot(
      snapshot([
        [OBJECT, 'Object', 28],
        [OBJECT, 'Object', 28],
        [OBJECT, 'Float64Array', 72],
        [CLOSURE, '', 32],
        [STRING, 'abc', 16],
        [STRING, 'defg', 20],
      ]),
    );
    expect(s.get('Object')).toEqual({ count: 2, bytes: 56 });
    expect(s.get('Float64Array')).toEqual({ count: 1, bytes: 72 });
    expect(s.get('closure (anonymous)')).toEqual({ count: 1, bytes: 32 });
    expect(s.get('(string)')).toEqual({ count: 2, bytes: 36 });
  });
});

describe('heapGrowth', () => {
  it('names what grew between two snapshots, biggest first, and leaves out what shrank', () => {
    const early = summarizeSnapshot(
      snapshot([
        [OBJECT, 'Object', 28],
        [OBJECT, 'Keep', 100],
      ]),
    );
    const late = summarizeSnapshot(
      snapshot([
        ...Array.from({ length: 50 }, (): [number, string, number] => [OBJECT, 'Object', 28]),
        [CLOSURE, '', 32],
        [CLOSURE, '', 32],
      ]),
    );
    const g = heapGrowth(early, late);
    expect(g.map((r) => r.name)).toEqual(['Object', 'closure (anonymous)']);
    expect(g[0]).toEqual({ name: 'Object', count: 49, bytes: 49 * 28, countAfter: 50 });
  });
});
