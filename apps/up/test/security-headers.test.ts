import { describe, expect, it } from 'vitest';
import {
  contentSecurityPolicy,
  parseExtraSources,
  securityHeaders,
} from '../src/security-headers.ts';

describe('the HUD security headers', () => {
  it('forbid framing, other scripts, sniffing and the referrer', () => {
    const h = securityHeaders();
    expect(h['x-frame-options']).toBe('DENY');
    expect(h['x-content-type-options']).toBe('nosniff');
    expect(h['referrer-policy']).toBe('no-referrer');
    expect(h['content-security-policy']).toContain("frame-ancestors 'none'");
    expect(h['content-security-policy']).toContain("script-src 'self';");
    expect(h['content-security-policy']).not.toMatch(/unsafe-eval|script-src[^;]*unsafe-inline/);
  });

  it('add named brokers and cameras to connect-src and img-src only', () => {
    const csp = contentSecurityPolicy({ extraSources: ['wss://b.lab:8884', 'http://10.0.0.5:*'] });
    expect(csp).toContain("connect-src 'self' wss://b.lab:8884 http://10.0.0.5:*;");
    expect(csp).toContain("img-src 'self' data: blob: wss://b.lab:8884 http://10.0.0.5:*;");
    expect(csp).toContain("script-src 'self';");
  });

  it('parse a list of sources, and refuse what could change the policy, naming it', () => {
    expect(parseExtraSources(' wss://b.lab:8884, https://*.cams.lab  http://[::1]:8080 ')).toEqual([
      'wss://b.lab:8884',
      'https://*.cams.lab',
      'http://[::1]:8080',
    ]);
    expect(parseExtraSources('')).toEqual([]);
    for (const bad of [
      'https://x;script-src',
      "'unsafe-inline'",
      'javascript:',
      'https://x/path',
      '*',
    ])
      expect(() => parseExtraSources(bad)).toThrow(/is not a source/);
  });
});
