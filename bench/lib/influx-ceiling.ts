/**
 * influxd's own ceiling, as the ingest section measures it: the points of N 6-servo state
 * groups, pre-formatted as the middleware's line protocol (and gzipped) before the clock starts,
 * POSTed straight to /api/v2/write by a client of a given shape. Returns points/s and CPU.
 */
import { gzipSync } from 'node:zlib';
import { angleFromPwm } from '@armtwin/protocol';
import { countPoints } from './stack.ts';
import { cpuMeter } from './proc.ts';
import { round } from './stats.ts';
import type { BenchContext } from './types.ts';

/** How a direct client writes: lines per request, requests in flight, gzip. */
export interface ClientShape {
  batch: number;
  writers: number;
  gzip: boolean;
}
/** influxd's best client: what its docs recommend (5,000-line batches, concurrent writers, gzip). */
export const BEST_CLIENT: ClientShape = { batch: 5000, writers: 4, gzip: true };
/** The old baseline: the middleware's batch size (BATCH_SIZE 1000), one request at a time, plain. */
export const SEQUENTIAL_CLIENT: ClientShape = { batch: 1000, writers: 1, gzip: false };

/** A ceiling: pre-formatted (and pre-gzipped) batches straight to /api/v2/write; points/s and CPU. */
export async function ceiling(
  ctx: BenchContext,
  groups: number,
  influxPid: number | undefined,
  arm: string,
  shape: ClientShape = BEST_CLIENT,
) {
  const t0us = Date.now() * 1000;
  const lines: string[] = [];
  for (let k = 0; k < groups; k++) {
    for (let id = 0; id < 6; id++) {
      const pwm = 1000 + ((k * 7 + id * 150) % 1000);
      lines.push(
        `servo,arm=${arm},id=00${id} pwm=${pwm}i,angle=${angleFromPwm(pwm)} ${t0us + k * 1000}`,
      );
    }
  }
  const bodies: (string | Buffer)[] = [];
  for (let i = 0; i < lines.length; i += shape.batch) {
    const body = lines.slice(i, i + shape.batch).join('\n');
    bodies.push(shape.gzip ? gzipSync(body) : body);
  }
  const headers: Record<string, string> = { 'content-type': 'text/plain' };
  if (shape.gzip) headers['content-encoding'] = 'gzip';
  const url = `${ctx.influx.url}/api/v2/write?bucket=${encodeURIComponent(ctx.influx.bucket)}&org=&precision=us`;
  // Warm-up: creates the shard and the series of the ceiling's arm before the clock starts.
  await fetch(url, { method: 'POST', body: lines.slice(0, 6 * 100).join('\n') }).then((r) =>
    r.arrayBuffer(),
  );
  const inf = influxPid ? cpuMeter(influxPid) : undefined;
  const self0 = process.cpuUsage();
  inf?.start();
  const w0 = performance.now();
  let failed = 0;
  let next = 0;
  const writer = async () => {
    while (next < bodies.length) {
      const res = await fetch(url, { method: 'POST', body: bodies[next++]! as BodyInit, headers });
      if (res.status !== 204) failed++;
      await res.arrayBuffer();
    }
  };
  await Promise.all(Array.from({ length: shape.writers }, writer));
  const wallS = (performance.now() - w0) / 1000;
  const influxCpu = inf?.stop();
  const self = process.cpuUsage(self0);
  const stored = await countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm);
  return {
    shape,
    points: lines.length,
    stored,
    failedRequests: failed,
    wallS: round(wallS, 3),
    pointsPerS: Math.round(lines.length / wallS),
    groupsPerS: Math.round(lines.length / 6 / wallS),
    clientCpuMsPer1000: round(((self.user + self.system) / 1000 / lines.length) * 1000, 3),
    influxdCpuMsPer1000: influxCpu ? round((influxCpu.cpuS * 1e6) / lines.length, 3) : NaN,
  };
}
