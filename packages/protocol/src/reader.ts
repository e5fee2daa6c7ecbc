import type { Frame, Group } from './frames.ts';
import type { ReaderError, ReaderErrorKind } from './errors.ts';
import { decodeCommonFrame, decodeFrame } from './decode.ts';
import { MAX_FRAME_LENGTH } from './limits.ts';

export interface ReaderOptions {
  /** A complete top-level frame (a `$TIM` frame is delivered here too). */
  onFrame?: (frame: Frame) => void;
  /** A complete `{…}` group. */
  onGroup?: (group: Group) => void;
  /** Dropped input, one call per dropped piece. */
  onError?: (error: ReaderError) => void;
  /** Longest frame accepted, `!` included; also the bound on the reader's buffer. */
  maxFrameLength?: number;
  /** Most frames one group may hold before it is cut off as unterminated. */
  maxGroupFrames?: number;
}

export const DEFAULT_READER_OPTIONS = {
  maxFrameLength: MAX_FRAME_LENGTH,
  maxGroupFrames: 256,
} as const;

export interface Reader {
  /** Feeds any chunk of the stream: several frames, part of one, junk. Never throws. */
  feed(chunk: string | Uint8Array): void;
  /** End of stream: reports a pending partial frame, junk run or open group. */
  flush(): void;
  /** Forgets everything pending (partial frame, junk, open group, stamp) without reporting it. */
  reset(): void;
  /** Forgets the `$TIM` stamp, so later frames carry none until the next `$TIM`. */
  clearStamp(): void;
  /** Characters held for an incomplete frame; never more than maxFrameLength. */
  readonly bufferedBytes: number;
}

const BANG = 33; // !
const HASH = 35; // #
const DOLLAR = 36; // $
const LBRACE = 123; // {
const RBRACE = 125; // }

const isStart = (c: number) => c === HASH || c === DOLLAR || c === LBRACE || c === RBRACE;
const isSpace = (c: number) => c === 32 || c === 9 || c === 10 || c === 13;

function latin1(bytes: Uint8Array): string {
  let text = '';
  for (let i = 0; i < bytes.length; i += 8192) {
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 8192) as unknown as number[]);
  }
  return text;
}

/**
 * The streaming frame reader: cuts on `!` across any chunk boundary, unpacks `{…}` groups,
 * stamps frames with the preceding `$TIM`, drops and reports junk (at its `!`, or at the next
 * frame start), resynchronises on the next `#`, `$`, `{` or `}`. Whitespace between frames is ignored. No timers, no I/O.
 */
export function createReader(options: ReaderOptions = {}): Reader {
  const opts = { ...DEFAULT_READER_OPTIONS, ...options };
  const maxLen = opts.maxFrameLength;
  let pending = ''; // an incomplete frame: starts with # or $, holds no terminator
  let junk = ''; // the start of the current junk run (reported when the run ends)
  let inJunk = false;
  let skipping = false; // the tail of an over-long frame: dropped silently until the next start
  let group: Frame[] | null = null;
  let groupInvalid = 0;
  let groupTime: number | undefined;
  let stamp: number | undefined;

  function report(kind: ReaderErrorKind, message: string, text: string) {
    if (group) groupInvalid++;
    opts.onError?.({ kind, message, text: text.slice(0, maxLen) });
  }

  function endJunk() {
    if (inJunk) report('junk', 'bytes between frames that are not a frame', junk);
    inJunk = false;
    junk = '';
    skipping = false;
  }

  function emitGroup() {
    const done: Group = { type: 'group', frames: group ?? [], invalid: groupInvalid };
    if (groupTime !== undefined) done.time = groupTime;
    group = null;
    groupInvalid = 0;
    opts.onGroup?.(done);
  }

  function cutGroup(message: string) {
    report('unterminated-group', message, '{');
    emitGroup();
  }

  /** The frame `s`[from, to): the common shapes read in place, the rest through decodeFrame. */
  function handleFrame(s: string, from: number, to: number) {
    let frame = decodeCommonFrame(s, from, to);
    if (!frame) {
      const result = decodeFrame(s.slice(from, to));
      if (!result.ok) {
        report(result.error.kind, result.error.message, result.error.text);
        return;
      }
      frame = result.frame;
    }
    if (frame.type === 'time') {
      stamp = frame.ms;
      opts.onFrame?.(frame);
      return;
    }
    if (stamp !== undefined) frame.time = stamp;
    if (!group) {
      opts.onFrame?.(frame);
    } else if (group.length < opts.maxGroupFrames) {
      group.push(frame);
    } else {
      cutGroup(`group longer than ${opts.maxGroupFrames} frames`);
      opts.onFrame?.(frame);
    }
  }

  function feed(chunk: string | Uint8Array) {
    const s = pending + (typeof chunk === 'string' ? chunk : latin1(chunk));
    pending = '';
    const n = s.length;
    let i = 0;
    while (i < n) {
      const c = s.charCodeAt(i);
      if (c === HASH || c === DOLLAR) {
        endJunk();
        let j = i + 1;
        let d = 0;
        for (; j < n; j++) {
          d = s.charCodeAt(j);
          if (d === BANG || isStart(d)) break;
        }
        if (j === n) {
          if (n - i >= maxLen) {
            report('too-long', `no "!" within ${maxLen} bytes`, s.slice(i, i + maxLen));
            skipping = true;
          } else {
            pending = s.slice(i);
          }
          return;
        }
        if (d === BANG) {
          if (j + 1 - i > maxLen)
            report('too-long', `frame longer than ${maxLen} bytes`, s.slice(i, j + 1));
          else handleFrame(s, i, j + 1);
          i = j + 1;
        } else {
          if (j - i >= maxLen) report('too-long', `no "!" within ${maxLen} bytes`, s.slice(i, j));
          else report('truncated', 'frame cut short by the next frame', s.slice(i, j));
          i = j;
        }
      } else if (c === LBRACE) {
        endJunk();
        if (group) cutGroup('"{" inside an open group');
        group = [];
        groupInvalid = 0;
        groupTime = stamp;
        i++;
      } else if (c === RBRACE) {
        endJunk();
        if (group) emitGroup();
        else report('unexpected-group-end', '"}" without an open group', '}');
        i++;
      } else if (!inJunk && !skipping && isSpace(c)) {
        i++;
      } else {
        // Junk runs to the next frame start, or through a `!`: the contract cuts on `!`, so
        // `hello world!` is reported when its `!` arrives, not when the next frame does.
        let j = c === BANG ? i + 1 : i;
        if (c !== BANG) {
          while (++j < n) {
            const d = s.charCodeAt(j);
            if (isStart(d)) break;
            if (d === BANG) {
              j++;
              break;
            }
          }
        }
        if (!skipping) {
          if (junk.length < maxLen) junk += s.slice(i, Math.min(j, i + maxLen - junk.length));
          inJunk = true;
        }
        i = j;
        if (s.charCodeAt(j - 1) === BANG) endJunk();
      }
    }
  }

  return {
    feed,
    flush() {
      if (pending) report('truncated', 'stream ended inside a frame', pending);
      pending = '';
      endJunk();
      if (group) cutGroup('stream ended inside a group');
    },
    reset() {
      pending = junk = '';
      inJunk = skipping = false;
      group = null;
      groupInvalid = 0;
      stamp = groupTime = undefined;
    },
    clearStamp() {
      stamp = undefined;
    },
    get bufferedBytes() {
      return pending.length;
    },
  };
}
