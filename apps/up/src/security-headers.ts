/**
 * The HUD's security headers (SECURITY.md § The page itself): a page that can move an arm must
 * not be framed by another site (a click through an invisible frame) nor run injected script.
 * Every response of `armtwin up`'s HTTP port carries them; deploy/nginx/armtwin.conf sets the
 * same ones in front of Mosquitto. Pure: the headers are a function of the options.
 *
 * What the built HUD needs, and why each source is there:
 * - scripts: only its own bundle (`script-src 'self'`; no inline script, no eval);
 * - styles: its own CSS file, plus inline style attributes React and three.js set;
 * - connections: the broker at /mqtt and the cameras served on this port ('self'), plus the
 *   `extraSources` an operator names (another broker, camera servers on other hosts or ports);
 * - pictures: its own, `data:`/`blob:` (model textures, canvas snapshots, CSV downloads), plus
 *   `extraSources`; workers from `blob:` (worker-timers keeps the deadman's beat in one).
 */

export interface HudHeadersOptions {
  /**
   * Sources beyond this origin the HUD may connect to and show pictures from: other brokers and
   * camera servers, as CSP sources (`wss://broker.lab:8884`, `https://cams.lab`, `http://10.0.0.5:*`).
   */
  extraSources: readonly string[];
}

export const DEFAULT_HUD_HEADERS_OPTIONS: HudHeadersOptions = { extraSources: [] };

/** A CSP host source with a scheme: `scheme://host[:port|:*]`, host may start with `*.`. */
const SOURCE = /^(https?|wss?):\/\/((\*\.)?[a-z0-9.-]+|\[[0-9a-f:]+\])(:(\d{1,5}|\*))?$/i;

/**
 * Splits and checks a list of extra sources (space- or comma-separated). Throws, naming the
 * first bad one, on anything that is not `http(s)://` or `ws(s)://` host[:port] (a path, a
 * quote, a `;` could change the policy itself).
 */
export function parseExtraSources(text: string): string[] {
  const list = text
    .split(/[\s,]+/)
    .map((s) => s.trim())
    .filter(Boolean);
  for (const s of list)
    if (!SOURCE.test(s))
      throw new Error(
        `"${s}" is not a source: expected scheme://host[:port], scheme http, https, ws or wss`,
      );
  return list;
}

/** The Content-Security-Policy header's value. */
export function contentSecurityPolicy(o: HudHeadersOptions = DEFAULT_HUD_HEADERS_OPTIONS): string {
  const extra = o.extraSources.length ? ` ${o.extraSources.join(' ')}` : '';
  return [
    "default-src 'self'",
    "script-src 'self'",
    "style-src 'self' 'unsafe-inline'",
    `img-src 'self' data: blob:${extra}`,
    "font-src 'self' data:",
    `connect-src 'self'${extra}`,
    "media-src 'self' blob:",
    "worker-src 'self' blob:",
    "object-src 'none'",
    "base-uri 'none'",
    "form-action 'self'",
    "frame-ancestors 'none'",
  ].join('; ');
}

/** Every header, for `res.writeHead` / `setHeader` (lower-case names). */
export function securityHeaders(
  o: HudHeadersOptions = DEFAULT_HUD_HEADERS_OPTIONS,
): Record<string, string> {
  return {
    'content-security-policy': contentSecurityPolicy(o),
    'x-frame-options': 'DENY',
    'x-content-type-options': 'nosniff',
    'referrer-policy': 'no-referrer',
  };
}
