/**
 * `/metrics`' text: every family once with its HELP and TYPE, labelled counters one row per
 * label value (escaped), flags as 1/0, and the write-latency histogram's cumulative buckets.
 */
import { describe, expect, it } from 'vitest';
import { Metrics, renderMetrics } from '../src/metrics.ts';

const P = 'armtwin_middleware_';

describe('renderMetrics', () => {
  it('shows every family once, each with HELP and TYPE, in Prometheus 0.0.4 text', () => {
    const text = renderMetrics(new Metrics());
    const types = [...text.matchAll(/^# TYPE (\S+) (\S+)$/gm)].map((m) => `${m[1]} ${m[2]}`);
    expect(types).toHaveLength(29);
    expect(new Set(types).size).toBe(29);
    expect(types).toContain(`${P}write_latency_seconds histogram`);
    expect(types).toContain(`${P}spool_full gauge`);
    expect(text.match(/^# HELP /gm)).toHaveLength(29);
    expect(text).toContain(`\n${P}points_dropped_total 0\n`);
    expect(text).toContain(`${P}write_batches_total{result="rejected"} 0\n`);
    expect(text.endsWith('\n')).toBe(true);
  });

  it('counts by label, writes flags as 1 and 0, and the histogram cumulatively', () => {
    const m = new Metrics();
    m.count(m.frames, 'position', 7);
    m.count(m.rejected, 'bad "topic"\\x');
    m.spoolFull = true;
    m.writeLatency.observe(0.03);
    m.writeLatency.observe(3);
    const text = renderMetrics(m);
    expect(text).toContain(`${P}frames_total{kind="position"} 7\n`);
    expect(text).toContain(`${P}frames_rejected_total{reason="bad \\"topic\\"\\\\x"} 1\n`);
    expect(text).toContain(`${P}spool_full 1\n`);
    expect(text).toContain(`${P}mqtt_connected 0\n`);
    expect(text).toContain(`${P}write_latency_seconds_bucket{le="0.025"} 0\n`);
    expect(text).toContain(`${P}write_latency_seconds_bucket{le="0.05"} 1\n`);
    expect(text).toContain(`${P}write_latency_seconds_bucket{le="5"} 2\n`);
    expect(text).toContain(`${P}write_latency_seconds_bucket{le="+Inf"} 2\n`);
    expect(text).toContain(`${P}write_latency_seconds_sum 3.03\n`);
    expect(text).toContain(`${P}write_latency_seconds_count 2\n`);
  });
});
