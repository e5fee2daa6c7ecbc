/**
 * Why a piece of input was dropped, declared once; counted per kind by every consumer.
 * - `junk`: bytes between frames that are not a frame (reported at their `!`, or at the next
 *   frame start `#`, `$`, `{`, `}`)
 * - `truncated`: a frame cut short by the next frame start before its `!`
 * - `too-long`: more than MAX_FRAME_LENGTH bytes without a `!`
 * - `malformed`: starts like a frame but matches no frame's syntax (e.g. a non-numeric field)
 * - `out-of-range`: the syntax matched but a field is out of range (pwm, id, ms, …)
 * - `unterminated-group`: a `{` opened while a group was open, or the group grew past its bound
 * - `unexpected-group-end`: a `}` with no open group
 */
export const READER_ERROR_KINDS = [
  'junk',
  'truncated',
  'too-long',
  'malformed',
  'out-of-range',
  'unterminated-group',
  'unexpected-group-end',
] as const;
export type ReaderErrorKind = (typeof READER_ERROR_KINDS)[number];

/** A counter per error kind, all zero. */
export const emptyErrorCounts = (): Record<ReaderErrorKind, number> =>
  Object.fromEntries(READER_ERROR_KINDS.map((k) => [k, 0])) as Record<ReaderErrorKind, number>;

export interface ReaderError {
  kind: ReaderErrorKind;
  /** one-line human-readable reason */
  message: string;
  /** the offending input (at most MAX_FRAME_LENGTH characters) */
  text: string;
}

/** Thrown by encoders given out-of-range values. Decoders never throw. */
export class ProtocolError extends Error {
  readonly kind: 'out-of-range' | 'malformed';
  constructor(kind: 'out-of-range' | 'malformed', message: string) {
    super(message);
    this.name = 'ProtocolError';
    this.kind = kind;
  }
}
