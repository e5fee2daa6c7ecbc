/** Why a piece of input was dropped. Counted per kind by every consumer. */
export type ReaderErrorKind =
  /** bytes between frames that are not a frame start (`#`, `$`, `{`, `}`) */
  | 'junk'
  /** a frame cut short by the next frame start before its `!` */
  | 'truncated'
  /** more than MAX_FRAME_LENGTH bytes without a `!` */
  | 'too-long'
  /** starts like a frame but matches no frame's syntax (e.g. a non-numeric field) */
  | 'malformed'
  /** the syntax matched but a field is out of range (pwm, id, ms, …) */
  | 'out-of-range'
  /** a `{` opened while a group was open, or the group grew past its bound */
  | 'unterminated-group'
  /** a `}` with no open group */
  | 'unexpected-group-end';

export const READER_ERROR_KINDS: readonly ReaderErrorKind[] = [
  'junk',
  'truncated',
  'too-long',
  'malformed',
  'out-of-range',
  'unterminated-group',
  'unexpected-group-end',
];

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
