/**
 * Reads a `multipart/x-mixed-replace` stream (an MJPEG camera over HTTP) part by part, pure and
 * browser-safe: fed chunks of any size, it calls back with each part's headers and body as soon
 * as the body is complete. A part with a `Content-Length` ends after that many bytes (no search,
 * no wait for the next boundary); one without ends at the next boundary. Bounded: headers over
 * `maxHeaderBytes` or a body over `maxPartBytes` are dropped and reported, and the parser finds
 * the next boundary.
 */
import { ByteBuffer } from './byte-buffer.ts';

/**
 * The multipart boundary of armtwin's MJPEG responses (./camera-feed.ts) and of the recorded
 * `.mjpeg` segments, which hold the same parts.
 */
export const MJPEG_BOUNDARY = 'armtwin-frame';

export const MULTIPART_ERRORS = [
  'junk',
  'headers-too-large',
  'part-too-large',
  'truncated',
] as const;
export type MultipartErrorKind = (typeof MULTIPART_ERRORS)[number];

export interface MultipartError {
  kind: MultipartErrorKind;
  message: string;
  bytes: number;
}

export interface MultipartPart {
  /** Header names in lower case. */
  headers: Record<string, string>;
  body: Uint8Array;
}

export interface MultipartParserOptions {
  /** The `boundary` parameter of the response's Content-Type (with or without a leading `--`). */
  boundary: string;
  onPart: (part: MultipartPart) => void;
  onError?: (error: MultipartError) => void;
  /** Largest body kept, bytes. */
  maxPartBytes?: number;
  /** Largest header block kept, bytes. */
  maxHeaderBytes?: number;
}

export const DEFAULT_MULTIPART_PARSER_OPTIONS = {
  maxPartBytes: 8 << 20,
  maxHeaderBytes: 8192,
} as const;

export interface MultipartParser {
  feed(chunk: Uint8Array): void;
  /** End of stream: reports a part still incomplete. */
  flush(): void;
  reset(): void;
  readonly bufferedBytes: number;
  /** The stream's closing boundary (`--boundary--`) was seen. */
  readonly closed: boolean;
}

/** The `boundary` parameter of a Content-Type header, or null. */
export function multipartBoundary(contentType: string | null | undefined): string | null {
  const m = /;\s*boundary=(?:"([^"]+)"|([^;\s]+))/i.exec(contentType ?? '');
  return m ? (m[1] ?? m[2] ?? null) : null;
}

const ascii = (s: string) => new TextEncoder().encode(s);
const CRLFCRLF = ascii('\r\n\r\n');
const LFLF = ascii('\n\n');
const LF = ascii('\n');
/** Transport padding allowed after a delimiter, before its line ends. */
const MAX_PADDING = 80;
const isSpace = (c: number | undefined) => c === 13 || c === 10 || c === 32 || c === 9;

function parseHeaders(block: Uint8Array): Record<string, string> {
  const headers: Record<string, string> = {};
  for (const line of new TextDecoder().decode(block).split(/\r?\n/)) {
    const colon = line.indexOf(':');
    if (colon > 0)
      headers[line.slice(0, colon).trim().toLowerCase()] = line.slice(colon + 1).trim();
  }
  return headers;
}

export function createMultipartParser(options: MultipartParserOptions): MultipartParser {
  const o = { ...DEFAULT_MULTIPART_PARSER_OPTIONS, ...options };
  const name = o.boundary.replace(/^--/, '');
  const delimiter = ascii(`--${name}`);
  const bodyEnd = ascii(`\r\n--${name}`);
  const buf = new ByteBuffer();
  type State = 'boundary' | 'headers' | 'body' | 'scan' | 'skip';
  let state: State = 'boundary';
  let headers: Record<string, string> = {};
  let need = 0; // body bytes still to come ('body'), or to skip ('skip')
  let scanned = 0; // where the next search starts, so a slow part is not searched twice
  let junk = 0; // bytes that are not whitespace, skipped since the last part
  let silent = false; // skipping the rest of a dropped part: not junk
  let dropping = false; // 'scan' of a part already reported too large
  let closed = false;

  const report = (kind: MultipartErrorKind, message: string, bytes: number) =>
    o.onError?.({ kind, message, bytes });
  const skip = (n: number) => {
    if (!silent) for (let i = 0; i < n; i++) if (!isSpace(buf.at(i))) junk++;
    buf.drop(n);
  };
  const endJunk = () => {
    if (junk) report('junk', 'bytes between parts that are not a part', junk);
    junk = 0;
    silent = false;
  };
  const toBoundary = (quiet: boolean) => {
    state = 'boundary';
    scanned = 0;
    silent = quiet;
  };

  function step(): boolean {
    switch (state) {
      case 'boundary': {
        const at = buf.indexOf(delimiter, scanned);
        if (at < 0) {
          // Keep what may be the start of a delimiter; what is before it cannot become one.
          skip(Math.max(0, buf.length - delimiter.length + 1));
          scanned = 0;
          return false;
        }
        // The rest of the delimiter line: `\r\n`, or `--` for the last one.
        const lineEnd = buf.indexOf(LF, at + delimiter.length);
        if (lineEnd < 0 || lineEnd - at > delimiter.length + MAX_PADDING) {
          if (buf.length - at <= delimiter.length + MAX_PADDING) {
            scanned = at;
            return false;
          }
          skip(at + delimiter.length); // not a delimiter line after all
          scanned = 0;
          return true;
        }
        skip(at);
        endJunk();
        const rest = new TextDecoder().decode(buf.view(delimiter.length, lineEnd - at)).trim();
        buf.drop(lineEnd - at + 1);
        scanned = 0;
        if (rest.startsWith('--')) closed = true;
        else state = 'headers';
        return true;
      }
      case 'headers': {
        if (buf.at(0) === 13 && buf.at(1) === 10) {
          buf.drop(2); // no headers: the blank line at once
          return startBody({});
        }
        let end = buf.indexOf(CRLFCRLF, scanned);
        let sep = 4;
        const lf = buf.indexOf(LFLF, scanned);
        if (lf >= 0 && (end < 0 || lf < end)) {
          end = lf;
          sep = 2;
        }
        if (end < 0 ? buf.length > o.maxHeaderBytes : end > o.maxHeaderBytes) {
          report(
            'headers-too-large',
            `part headers over ${o.maxHeaderBytes} bytes`,
            o.maxHeaderBytes,
          );
          toBoundary(true);
          return true;
        }
        if (end < 0) {
          scanned = Math.max(0, buf.length - 3);
          return false;
        }
        scanned = 0;
        const h = parseHeaders(buf.view(0, end));
        buf.drop(end + sep);
        return startBody(h);
      }
      case 'body': {
        if (buf.length < need) return false;
        o.onPart({ headers, body: buf.take(need) });
        toBoundary(false);
        return true;
      }
      case 'skip': {
        const n = Math.min(need, buf.length);
        buf.drop(n);
        need -= n;
        if (need > 0) return false;
        toBoundary(false);
        return true;
      }
      case 'scan': {
        const at = buf.indexOf(bodyEnd, scanned);
        if (!dropping && (at < 0 ? buf.length > o.maxPartBytes : at > o.maxPartBytes)) {
          report('part-too-large', `part over ${o.maxPartBytes} bytes`, o.maxPartBytes);
          dropping = true;
        }
        if (at < 0) {
          const keep = bodyEnd.length - 1;
          if (dropping && buf.length > keep) buf.drop(buf.length - keep);
          scanned = Math.max(0, buf.length - keep);
          return false;
        }
        if (dropping) buf.drop(at);
        else o.onPart({ headers, body: buf.take(at) });
        dropping = false;
        toBoundary(false);
        return true;
      }
    }
  }

  function startBody(h: Record<string, string>): boolean {
    headers = h;
    const length = /^\d{1,12}$/.test(h['content-length'] ?? '') ? Number(h['content-length']) : -1;
    if (length > o.maxPartBytes) {
      report('part-too-large', `part of ${length} bytes, over ${o.maxPartBytes}`, length);
      need = length;
      state = 'skip';
    } else if (length >= 0) {
      need = length;
      state = 'body';
    } else state = 'scan';
    return true;
  }

  const clear = () => {
    buf.clear();
    toBoundary(false);
    junk = 0;
    dropping = false;
  };

  return {
    feed(chunk) {
      if (closed) return;
      buf.append(chunk);
      while (!closed && step());
    },
    flush() {
      if (closed) return clear(); // what follows the closing boundary is an epilogue
      const started = state !== 'headers' || buf.length > 0;
      if (state !== 'boundary' && state !== 'skip' && !dropping && started)
        report('truncated', 'part cut off at the end of the stream', buf.length);
      else if (state === 'boundary') skip(buf.length);
      endJunk();
      clear();
    },
    reset() {
      clear();
      closed = false;
    },
    get bufferedBytes() {
      return buf.length;
    },
    get closed() {
      return closed;
    },
  };
}
