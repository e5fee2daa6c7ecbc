/**
 * The InfluxDB edge: write a body of line protocol, ping, create the database or bucket.
 * Writes go through the official client's HTTP transport (`InfluxDB.transport`), NOT its
 * WriteApi: the WriteApi drops lines when its retries run out (maxRetryTime 180 s), when its
 * retry buffer overflows (maxBufferLines; RetryBuffer.addLines removes the oldest items) and
 * on close() (RetryBuffer.close() returns the unsent count and they are logged, not kept).
 * Retrying is the shipper's job, against the durable spool.
 */
import { promisify } from 'node:util';
import zlib from 'node:zlib';
import { HttpError, InfluxDB } from '@influxdata/influxdb-client';
import { BucketsAPI, OrgsAPI } from '@influxdata/influxdb-client-apis';

export interface InfluxWriter {
  /** POSTs line protocol (µs precision). Rejects with a WriteError. */
  write(body: string): Promise<void>;
  /** true when the server answers /ping. */
  ping(): Promise<boolean>;
  /** Detects 1.x/2.x and creates the database/bucket when missing; returns what it did. */
  ensureBucket(): Promise<string>;
}

export interface InfluxWriterOptions {
  url: string;
  token: string;
  org: string;
  /** 2.x bucket, or `db/rp` on 1.8. */
  bucket: string;
  /** Request timeout, ms. */
  timeoutMs: number;
  /**
   * gzip bodies at this zlib level (`Content-Encoding: gzip`, compressed off the main thread by
   * zlib); 0 or absent = plain. The client's own gzip has no level (zlib's default, 6).
   */
  gzipLevel?: number;
}

/** Bodies shorter than this go uncompressed (gzip would not pay). */
const GZIP_THRESHOLD_BYTES = 1000;

const gzip = promisify(zlib.gzip);

/** True for `localhost`, `127.x.x.x` and `[::1]`: InfluxDB on this machine. */
export function isLoopbackUrl(url: string): boolean {
  let host: string;
  try {
    host = new URL(url).hostname;
  } catch {
    return false;
  }
  return host === 'localhost' || host === '[::1]' || /^127\.\d+\.\d+\.\d+$/.test(host);
}

/**
 * The gzip level writes use (0 = plain) for WRITE_GZIP and WRITE_GZIP_LEVEL: `auto` gzips only
 * to an InfluxDB elsewhere. On loopback gzip saves no bandwidth, and its CPU (deflate here,
 * inflate in influxd) was the largest single cost of the middleware's profile (BENCHMARKS.md §2).
 */
export function gzipLevelFor(setting: 'auto' | boolean, level: number, influxUrl: string): number {
  const on = setting === 'auto' ? !isLoopbackUrl(influxUrl) : setting;
  return on ? level : 0;
}

/** Why a write failed: `data` = InfluxDB refused the points themselves (do not retry them). */
export class WriteError extends Error {
  constructor(
    readonly kind: 'data' | 'http' | 'network' | 'not-found' | 'auth',
    message: string,
    readonly status?: number,
  ) {
    super(message);
  }
}

/** Maps a failure to a WriteError kind. A 400/422 about the data is the data's fault. */
export function classifyWriteError(err: unknown): WriteError {
  if (err instanceof WriteError) return err;
  if (err instanceof HttpError) {
    const text =
      `${err.statusCode} ${err.json?.error ?? err.json?.message ?? err.body ?? err.message}`.slice(
        0,
        300,
      );
    if (err.statusCode === 404) return new WriteError('not-found', text, err.statusCode);
    if (err.statusCode === 401 || err.statusCode === 403)
      return new WriteError('auth', text, err.statusCode);
    const orgOrBucket =
      /organi[sz]ation|\borg\b|bucket|database/i.test(text) && !/partial write/i.test(text);
    if (
      (err.statusCode === 400 || err.statusCode === 413 || err.statusCode === 422) &&
      !orgOrBucket
    ) {
      return new WriteError('data', text, err.statusCode);
    }
    return new WriteError('http', text, err.statusCode);
  }
  return new WriteError('network', (err as Error)?.message ?? String(err));
}

/** True for an InfluxDB 2.x `X-Influxdb-Version` header. */
export const isV2 = (version: string): boolean => /^v?2\./.test(version);

export function createInfluxWriter(opts: InfluxWriterOptions): InfluxWriter {
  const url = opts.url.replace(/\/+$/, '');
  const influx = new InfluxDB({ url, token: opts.token || undefined, timeout: opts.timeoutMs });
  const path =
    `/api/v2/write?org=${encodeURIComponent(opts.org)}` +
    `&bucket=${encodeURIComponent(opts.bucket)}&precision=us`;
  const authHeader: Record<string, string> = opts.token
    ? { authorization: `Token ${opts.token}` }
    : {};
  const plain = { method: 'POST', headers: { 'content-type': 'text/plain; charset=utf-8' } };
  const gzipped = {
    method: 'POST',
    headers: { 'content-type': 'text/plain; charset=utf-8', 'content-encoding': 'gzip' },
  };
  const level = opts.gzipLevel ?? 0;
  // `send`, not `request`: request JSON-encodes a body that is not a string; send copies it with
  // Buffer.from, which takes the gzipped bytes as they are. Status ≥ 300 comes as an HttpError.
  const send = (body: string | Buffer, options: typeof plain) =>
    new Promise<void>((resolve, reject) =>
      influx.transport.send(path, body as string, options, {
        error: reject,
        complete: () => resolve(),
      }),
    );

  async function version(): Promise<string> {
    const res = await fetch(`${url}/ping`, {
      signal: AbortSignal.timeout(opts.timeoutMs),
      headers: authHeader,
    });
    return res.headers.get('x-influxdb-version') ?? '';
  }

  return {
    async write(body) {
      try {
        if (level > 0 && body.length >= GZIP_THRESHOLD_BYTES)
          await send(await gzip(body, { level }), gzipped);
        else await send(body, plain);
      } catch (err) {
        throw classifyWriteError(err);
      }
    },
    async ping() {
      try {
        const res = await fetch(`${url}/ping`, { signal: AbortSignal.timeout(2000) });
        return res.status < 500;
      } catch {
        return false;
      }
    },
    async ensureBucket() {
      // 2.x answers `X-Influxdb-Version: v2.x.y`; 1.x says `1.8.10`. A build from source without
      // version flags says `unknown` (1.x, like .tools/bin/influxd) or `dev` (2.x): then only
      // 2.x has the setup endpoint.
      const v = await version();
      const v2 =
        isV2(v) ||
        (!/^v?1\./.test(v) &&
          (await fetch(`${url}/api/v2/setup`, { signal: AbortSignal.timeout(opts.timeoutMs) })).ok);
      if (!v2) {
        const db = opts.bucket.split('/')[0] ?? opts.bucket;
        const headers: Record<string, string> = { ...authHeader };
        if (opts.token.includes(':')) {
          const [u, p] = opts.token.split(':', 2);
          headers.authorization = `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
        }
        const q = `CREATE DATABASE "${db.replace(/"/g, '\\"')}"`;
        const res = await fetch(`${url}/query`, {
          method: 'POST',
          headers,
          body: new URLSearchParams({ q }),
        });
        const text = await res.text();
        if (!res.ok || text.includes('"error"'))
          throw new Error(`${q} failed: ${res.status} ${text.slice(0, 200)}`);
        return `InfluxDB ${v || '1.x'} (1.x API): database "${db}" ready (CREATE DATABASE is idempotent)`;
      }
      const orgs = await new OrgsAPI(influx).getOrgs({ org: opts.org });
      const orgID = orgs.orgs?.[0]?.id;
      if (!orgID) throw new Error(`InfluxDB ${v}: organisation "${opts.org}" not found`);
      const buckets = new BucketsAPI(influx);
      try {
        const found = await buckets.getBuckets({ orgID, name: opts.bucket });
        if (found.buckets?.length) return `InfluxDB ${v}: bucket "${opts.bucket}" exists`;
      } catch (err) {
        if (!(err instanceof HttpError && err.statusCode === 404)) throw err;
      }
      await buckets.postBuckets({ body: { orgID, name: opts.bucket, retentionRules: [] } });
      return `InfluxDB ${v}: bucket "${opts.bucket}" created`;
    },
  };
}
