/**
 * The one `Range: bytes=…` a `<video>` sends to seek (RFC 9110 §14), pure. Node's HTTP server
 * has no ranges and the few lines here are all a file route needs: one range, first-last,
 * first- or -suffix. Anything else — no header, another unit, several ranges, a malformed or
 * backwards range — is ignored, as RFC 9110 lets a server do, and the whole file is sent.
 */

/** Inclusive byte offsets. */
export interface ByteRange {
  start: number;
  end: number;
}

const RANGE = /^bytes=(\d{0,15})-(\d{0,15})$/;

/** The range of a file of `size` bytes to send: a range, `unsatisfiable` (416), or null (200). */
export function byteRange(
  header: string | undefined,
  size: number,
): ByteRange | 'unsatisfiable' | null {
  const m = RANGE.exec((header ?? '').replace(/\s+/g, ''));
  if (!m) return null;
  const [, first = '', last = ''] = m;
  if (first === '' && last === '') return null;
  if (first === '') {
    // the last n bytes
    const n = Number(last);
    if (n === 0 || size === 0) return 'unsatisfiable';
    return { start: Math.max(0, size - n), end: size - 1 };
  }
  const start = Number(first);
  if (last !== '' && Number(last) < start) return null;
  if (start >= size) return 'unsatisfiable';
  return { start, end: last === '' ? size - 1 : Math.min(Number(last), size - 1) };
}
