/**
 * The deadman on `arm/{id}/operator`, the same for every driver: an `OperatorWatch` (a `0`, or a
 * beating operator whose lease ran out) whose let-go asks the driver to stop a moving arm
 * (`stop`: the driver's `operatorLeft`, true when something was moving and stopped) and notes
 * the first stop of each reason (`deadman:released`, `deadman:lapsed`) with `onFirst`. Pure: the
 * timers are injected.
 */
import {
  OPERATOR_LEASE_MS,
  OperatorWatch,
  type LetGoReason,
  type OperatorTimers,
} from '@armtwin/protocol';

const WORDS: Record<LetGoReason, string> = {
  released: 'operator gone while the arm moved: the arm holds where it is',
  lapsed: 'operator stopped beating while the arm moved: the arm holds where it is',
};

export function operatorDeadman(
  timers: OperatorTimers,
  stop: () => boolean,
  onFirst: (kind: string, message: string) => void,
  leaseMs: number = OPERATOR_LEASE_MS,
): OperatorWatch {
  return new OperatorWatch(
    timers,
    (reason) => {
      if (stop()) onFirst(`deadman:${reason}`, WORDS[reason]);
    },
    leaseMs,
  );
}
