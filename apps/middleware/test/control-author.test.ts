import { describe, expect, test } from 'vitest';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

const T = 1_700_000_000_000;

describe('commands on per-user control topics (docs/protocol.md § Control)', () => {
  test('are stored like plain ones, with the author as the tag user', () => {
    const ingest = new Ingest(new Metrics());
    const plain = ingest.handle('arm/arm1/control', `$TIM:${T}!#000P1500T1000!`, 5);
    const alice = ingest.handle('arm/arm1/control/alice', `$TIM:${T + 1}!#000P1600T1000!`, 5);
    expect(plain).toHaveLength(1);
    expect(plain[0]).not.toContain('user=');
    expect(alice).toHaveLength(1);
    expect(alice[0]).toMatch(/^command,arm=arm1,.*,user=alice pwm=1600i/);
  });

  test('other per-user topics are not commands', () => {
    const metrics = new Metrics();
    const ingest = new Ingest(metrics);
    expect(ingest.handle('arm/arm1/claim/alice', 'take', 5)).toEqual([]);
    expect(metrics.rejected['bad-topic']).toBe(1);
  });
});
