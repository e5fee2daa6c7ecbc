/** The bridge's stdout lines: events parsed, anything else refused with what it was. */
import { expect, test } from 'vitest';
import { parseEvent } from '../src/wire.ts';

test('events of every kind parse; other lines do not', () => {
  expect(parseEvent('{"ev":"ready","domain":7,"node":"n"}')).toEqual({
    ok: true,
    event: { ev: 'ready', domain: 7, node: 'n' },
  });
  expect(parseEvent('{"ev":"ack","id":3,"subscribers":1}')).toMatchObject({ ok: true });
  const js = parseEvent(
    '{"ev":"message","topic":"/j","type":"joint_state","msg":{"stamp_ms":5,"name":["a"],"position":[1],"velocity":[],"effort":[]}}',
  );
  expect(js).toMatchObject({
    ok: true,
    event: { type: 'joint_state', msg: { name: ['a'], position: [1] } },
  });
  expect(
    parseEvent(
      '{"ev":"message","topic":"/t","type":"joint_trajectory","msg":{"joint_names":["a"],"points":[{"positions":[1],"time_from_start_ms":10}]}}',
    ),
  ).toMatchObject({ ok: true });
  expect(parseEvent('{"ev":"error","kind":"bad-message","message":"m","id":null}')).toMatchObject({
    ok: true,
  });
  expect(parseEvent('Traceback (most recent call last):')).toMatchObject({
    ok: false,
    error: expect.stringContaining('not JSON'),
  });
  expect(
    parseEvent('{"ev":"message","topic":"/j","type":"joint_state","msg":{"name":"a"}}'),
  ).toMatchObject({ ok: false });
  expect(parseEvent('{"ev":"error","kind":"other","message":"m"}')).toMatchObject({ ok: false });
});
