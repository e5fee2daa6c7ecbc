/**
 * Issue 7 in the middleware: the API token on /metrics and /history (not /healthz), oversize
 * messages refused and counted, hostile topics dropped and counted, the readers map bounded.
 */
import { EventEmitter } from 'node:events';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { describe, expect, test } from 'vitest';
import { loadConfig } from '../src/config.ts';
import { createHttpHandler, type HealthReport } from '../src/http.ts';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

function call(handler: ReturnType<typeof createHttpHandler>, url: string, auth?: string) {
  const req = {
    url,
    method: 'GET',
    headers: auth ? { authorization: auth } : {},
  } as IncomingMessage;
  const res = Object.assign(new EventEmitter(), {
    status: 0,
    headersSent: false,
    writeHead(status: number) {
      res.status = status;
      return res;
    },
    end() {
      return res;
    },
  });
  handler(req, res as unknown as ServerResponse);
  return res.status;
}

describe('API token', () => {
  const health = () => ({ ok: true }) as HealthReport;
  const history = async (_req: IncomingMessage, res: ServerResponse) => (
    res.writeHead(200).end(),
    true
  );

  test('with API_TOKEN: /metrics and /history need the bearer token; /healthz stays open', () => {
    const h = createHttpHandler({ metrics: new Metrics(), health, history, apiToken: 's3cret' });
    expect(call(h, '/healthz')).toBe(200);
    expect(call(h, '/api/healthz')).toBe(200);
    expect(call(h, '/metrics')).toBe(401);
    expect(call(h, '/api/metrics', 'Bearer wrong')).toBe(401);
    expect(call(h, '/api/metrics', 'Basic czNjcmV0')).toBe(401);
    expect(call(h, '/history/series?arm=arm1')).toBe(401);
    expect(call(h, '/metrics', 'Bearer s3cret')).toBe(200);
    expect(call(h, '/api/history/series?arm=arm1', 'bearer s3cret')).toBe(200);
  });

  test('without it the API is open (the local demo)', () => {
    const h = createHttpHandler({ metrics: new Metrics(), health, history });
    expect(call(h, '/metrics')).toBe(200);
  });

  test('API_TOKEN and MAX_PAYLOAD_BYTES come from the environment', () => {
    const c = loadConfig({ API_TOKEN: 'abc', MAX_PAYLOAD_BYTES: '1024' });
    expect([c.apiToken, c.maxPayloadBytes]).toEqual(['abc', 1024]);
    expect(loadConfig({}).maxPayloadBytes).toBe(65536);
    expect(() => loadConfig({ API_TOKEN: 'a b' })).toThrow(/API_TOKEN/);
  });
});

describe('Ingest bounds', () => {
  test('an oversize message is refused whole and counted once', () => {
    const m = new Metrics();
    const ingest = new Ingest(m, undefined, { maxPayloadBytes: 100 });
    expect(ingest.handle('arm/arm1/status', '#000P1500!'.repeat(11), 0)).toEqual([]);
    expect(m.rejected).toEqual({ oversize: 1 });
    expect(ingest.handle('arm/arm1/status', '#000P1500!'.repeat(10), 0)).toHaveLength(10);
  });

  test('hostile topics never reach line protocol: dropped as bad-topic', () => {
    const m = new Metrics();
    const ingest = new Ingest(m);
    for (const arm of ['a"b', 'a,b', 'a b', 'a\nb', 'a\\b', 'a=b', 'A1', ''])
      expect(ingest.handle(`arm/${arm}/status`, '#000P1500!', 0)).toEqual([]);
    expect(m.rejected).toEqual({ 'bad-topic': 8 });
  });

  test('the readers map is bounded: the oldest is forgotten', () => {
    const m = new Metrics();
    const ingest = new Ingest(m, undefined, { maxReaders: 3 });
    for (let i = 0; i < 10; i++) ingest.handle(`arm/arm${i}/status`, '#000P15', 0);
    expect((ingest as unknown as { readers: Map<string, unknown> }).readers.size).toBe(3);
  });
});
