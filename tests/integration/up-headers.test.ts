/**
 * The HUD's security headers from `armtwin up` (SECURITY.md § The page itself): every answer of
 * its HTTP port (the page, its models, /api) says that no other site may frame it, that only its
 * own scripts run, where it may connect (this origin plus the sources named with
 * `--csp-sources`), no MIME sniffing and no referrer. A bad source is refused at start.
 */
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freePorts } from '../helpers/services.ts';
import { runNode, startUpProcess, type Child } from './sim-helpers.ts';

let up: Child;
let base = '';

beforeAll(async () => {
  const [httpPort = 0, mqttPort = 0] = await freePorts(2);
  up = await startUpProcess(
    ['scripts/start.mjs'],
    ['--no-middleware', '--no-web', '--csp-sources', 'wss://broker.lab:8884 http://10.0.0.5:*'],
    { httpPort, mqttPort },
  );
  base = `http://127.0.0.1:${httpPort}`;
});

afterAll(async () => {
  await up?.stop('SIGKILL');
});

/** The CSP's directives by name. */
function directives(csp: string): Map<string, string[]> {
  return new Map(
    csp
      .split(';')
      .map((d) => d.trim().split(/\s+/))
      .filter((d) => d[0])
      .map(([name, ...values]) => [name!, values]),
  );
}

describe('armtwin up: security headers', () => {
  for (const path of ['/', '/index.html', '/models/armtwin5/profile.json', '/api/whoami']) {
    test(`${path} carries them`, async () => {
      const res = await fetch(`${base}${path}`, { method: path === '/' ? 'HEAD' : 'GET' });
      expect(res.headers.get('x-frame-options')).toBe('DENY');
      expect(res.headers.get('x-content-type-options')).toBe('nosniff');
      expect(res.headers.get('referrer-policy')).toBe('no-referrer');
      const csp = directives(res.headers.get('content-security-policy') ?? '');
      expect(csp.get('frame-ancestors')).toEqual(["'none'"]);
      expect(csp.get('script-src')).toEqual(["'self'"]);
      expect(csp.get('default-src')).toEqual(["'self'"]);
      expect(csp.get('object-src')).toEqual(["'none'"]);
      expect(csp.get('connect-src')).toEqual([
        "'self'",
        'wss://broker.lab:8884',
        'http://10.0.0.5:*',
      ]);
      expect(csp.get('img-src')).toEqual(expect.arrayContaining(['http://10.0.0.5:*']));
    });
  }

  test('a source that could change the policy is refused at start, named', async () => {
    const bad = runNode([
      'scripts/start.mjs',
      '--no-middleware',
      '--no-web',
      '--port',
      '0',
      '--csp-sources',
      "https://x; script-src 'unsafe-inline'",
    ]);
    const code = await new Promise<number | null>((resolve) =>
      bad.proc.exitCode !== null ? resolve(bad.proc.exitCode) : bad.proc.once('exit', resolve),
    );
    expect(code).not.toBe(0);
    expect(bad.output()).toContain('"https://x;" is not a source');
  });
});
