import { describe, expect, test } from 'vitest';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

const T = 1_700_000_000_000;

describe('control events on arm/{id}/audit (docs/protocol.md § Control)', () => {
  test('become one audit point at their own time: the kind a tag, who and what as strings', () => {
    const ingest = new Ingest(new Metrics());
    const event = { at: T, by: 'alice', kind: 'granted', detail: 'alice gave control to "bob"' };
    expect(ingest.handle('arm/arm1/audit', JSON.stringify(event), 5)).toEqual([
      `audit,arm=arm1,kind=granted by="alice",detail="alice gave control to \\"bob\\"" ${T * 1000}`,
    ]);
    // The plain topic's author is '', a backslash and a line break stay inside the string.
    const odd = { at: T + 1, by: '', kind: 'refused-command', detail: 'a\\b\nc' };
    expect(ingest.handle('arm/arm1/audit', JSON.stringify(odd), 5)).toEqual([
      `audit,arm=arm1,kind=refused-command by="",detail="a\\\\b c" ${(T + 1) * 1000}`,
    ]);
  });

  test('anything else on the topic is refused, counted, and stores nothing', () => {
    const metrics = new Metrics();
    const ingest = new Ingest(metrics);
    for (const bad of ['not json', '{"at":1,"by":"x","kind":"made-up","detail":""}', '{}'])
      expect(ingest.handle('arm/arm1/audit', bad, 5)).toEqual([]);
    expect(ingest.handle('arm/BAD ARM/audit', '{}', 5)).toEqual([]);
    expect(metrics.rejected['bad-audit']).toBe(3);
    expect(metrics.rejected['bad-topic']).toBe(1);
  });
});
