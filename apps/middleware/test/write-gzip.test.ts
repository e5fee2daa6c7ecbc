import { describe, expect, test } from 'vitest';
import { loadConfig } from '../src/config.ts';
import { gzipLevelFor, isLoopbackUrl } from '../src/influx.ts';

describe('WRITE_GZIP', () => {
  test('auto (the default) writes plain to an InfluxDB on this machine, gzip level 1 elsewhere', () => {
    const c = loadConfig({});
    expect([c.writeGzip, c.writeGzipLevel]).toEqual(['auto', 1]);
    const level = (url: string) => gzipLevelFor(c.writeGzip, c.writeGzipLevel, url);
    expect(level('http://127.0.0.1:8086')).toBe(0);
    expect(level('http://localhost:8086/')).toBe(0);
    expect(level('http://[::1]:8086')).toBe(0);
    expect(level('http://127.5.0.9:8086')).toBe(0);
    expect(level('http://influx:8086')).toBe(1);
    expect(level('https://eu-central-1-1.aws.cloud2.influxdata.com')).toBe(1);
    expect(level('http://10.0.0.7:8086')).toBe(1);
    expect(level('http://127.0.0.1.example.com:8086')).toBe(1);
  });

  test('true and false win over the address; the level is 1–9', () => {
    const on = loadConfig({ WRITE_GZIP: 'true', WRITE_GZIP_LEVEL: '6' });
    expect(gzipLevelFor(on.writeGzip, on.writeGzipLevel, 'http://127.0.0.1:8086')).toBe(6);
    const off = loadConfig({ WRITE_GZIP: '0' });
    expect(gzipLevelFor(off.writeGzip, off.writeGzipLevel, 'http://influx:8086')).toBe(0);
    expect(() => loadConfig({ WRITE_GZIP_LEVEL: '0' })).toThrow(/WRITE_GZIP_LEVEL="0"/);
    expect(() => loadConfig({ WRITE_GZIP: 'yes' })).toThrow(/WRITE_GZIP="yes"/);
    expect(isLoopbackUrl('not a url')).toBe(false);
  });
});
