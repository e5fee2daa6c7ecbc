/**
 * Sends a robot (one .zip) to `armtwin up` to import (`POST <api>/robots/import`, an operator's
 * right, answered by packages/http-api/src/robots/import.ts) with the page's log-in. Too big is refused
 * here at once, before anything is sent.
 */
import { MAX_IMPORT_BYTES } from '@armtwin/robot';
import { authHeaders } from '../../../core/auth/whoami.ts';
import type { HudSettings } from '../../../core/config/settings.ts';

export type ImportAnswer =
  | { ok: true; name: string; files: number; warnings: string[]; notes: string[] }
  | { ok: false; errors: string[] };

const strings = (v: unknown): string[] => (Array.isArray(v) ? v.map(String) : []);

export async function sendImport(
  settings: Pick<HudSettings, 'apiBase' | 'username' | 'password'>,
  zip: Uint8Array,
  opts: { name?: string; urdf?: string; replace?: boolean } = {},
  fetchFn: typeof fetch = (url, init) => globalThis.fetch(url, init),
): Promise<ImportAnswer> {
  if (zip.length > MAX_IMPORT_BYTES)
    return {
      ok: false,
      errors: [
        `too big: ${(zip.length / 1048576).toFixed(0)} MB, at most ${MAX_IMPORT_BYTES / 1048576} MB`,
      ],
    };
  const q = new URLSearchParams();
  if (opts.name) q.set('name', opts.name);
  if (opts.urdf) q.set('urdf', opts.urdf);
  if (opts.replace) q.set('replace', '1');
  try {
    const res = await fetchFn(`${settings.apiBase}/robots/import${q.size ? `?${q}` : ''}`, {
      method: 'POST',
      headers: { 'content-type': 'application/zip', ...authHeaders(settings) },
      body: new Blob([zip as Uint8Array<ArrayBuffer>]),
      cache: 'no-store',
      credentials: 'omit',
    });
    const b = (await res.json().catch(() => null)) as Record<string, unknown> | null;
    if (res.ok && b && typeof b.name === 'string')
      return {
        ok: true,
        name: b.name,
        files: Number(b.files),
        warnings: strings(b.warnings),
        notes: strings(b.notes),
      };
    const errors = strings(b?.errors);
    return { ok: false, errors: errors.length ? errors : [`HTTP ${res.status}`] };
  } catch (err) {
    return { ok: false, errors: [`not sent: ${err instanceof Error ? err.message : String(err)}`] };
  }
}
