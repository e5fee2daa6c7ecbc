import { expect, test } from 'vitest';
import { PerishableInFlight } from '../src/perishable.ts';

test('only what was sent and not acknowledged on the closed connection is dropped, once', () => {
  const f = new PerishableInFlight();
  f.sent(1, 'arm/a/claim/u');
  f.sent(2, 'arm/a/control/u');
  f.sent(3, 'arm/a/claim/u');
  f.acknowledged(2);
  f.acknowledged(9); // not ours: ignored
  expect(f.closed()).toEqual([
    [1, 'arm/a/claim/u'],
    [3, 'arm/a/claim/u'],
  ]);
  expect(f.closed()).toEqual([]);
  // A message id is reused on the next connection: it is that message's now.
  f.sent(1, 'arm/a/control/u');
  expect(f.closed()).toEqual([[1, 'arm/a/control/u']]);
});
