/** Option parsers the commands share: bounded numbers, arm ids, the operator lease. */
import { InvalidArgumentError, Option } from 'commander';
import { isValidArmId, OPERATOR_LEASE_MS } from '@armtwin/protocol';

export const number =
  (name: string, min: number, max: number, integer = false) =>
  (value: string): number => {
    const n = Number(value);
    if (
      value.trim() === '' ||
      !Number.isFinite(n) ||
      n < min ||
      n > max ||
      (integer && !Number.isInteger(n))
    ) {
      throw new InvalidArgumentError(
        `${name} must be ${integer ? 'an integer' : 'a number'} in ${min}–${max}`,
      );
    }
    return n;
  };

export const armId = (value: string): string => {
  if (!isValidArmId(value)) throw new InvalidArgumentError('arm id must match [a-z0-9-]{1,32}');
  return value;
};

/** `--operator-lease <ms>`, shared by sim and gateway. */
export const operatorLeaseOption = () =>
  new Option(
    '--operator-lease <ms>',
    'let a beating operator go after this long without a 1 on arm/{id}/operator (0 = only its 0)',
  )
    .argParser(number('operator lease', 0, 600_000, true))
    .default(OPERATOR_LEASE_MS);
