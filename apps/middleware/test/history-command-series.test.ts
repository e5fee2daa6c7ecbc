/** `field=command`: the commanded angle series the HUD's History panel draws against the actual. */
import { describe, expect, test } from 'vitest';
import { seriesQuery } from '../src/history/queries.ts';
import { parseParams } from '../src/history/params.ts';

const NOW = 1_700_000_300_000;

describe('series of the commanded angle', () => {
  test('field=command is accepted and reads measurement command, field angle', () => {
    const parsed = parseParams(
      'series',
      new URLSearchParams('arm=arm1&id=002&field=command&start=-5m'),
      NOW,
      31 * 86_400_000,
    );
    expect(parsed.ok).toBe(true);
    if (!parsed.ok) return;
    const q = String(seriesQuery('armtwin/autogen', parsed.params, '200ms'));
    expect(q).toContain(
      'r._measurement == "command" and r.arm == "arm1" and (r._field == "angle") and (r.id == "002")',
    );
    expect(q).toContain('fn: mean');
  });

  test('the other fields still read the servo measurement', () => {
    const parsed = parseParams('series', new URLSearchParams('arm=arm1&field=angle'), NOW, 1e10);
    if (!parsed.ok) throw new Error(parsed.error);
    expect(String(seriesQuery('b', parsed.params, '1s'))).toContain(
      'r._measurement == "servo" and r.arm == "arm1" and (r._field == "angle")',
    );
  });
});
