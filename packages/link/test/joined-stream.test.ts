import { describe, expect, test } from 'vitest';
import { joinedStream } from '../src/joined-stream.ts';

/** A client that holds each message until `ack()`: what it was handed, in order. */
function slowClient() {
  const sent: string[] = [];
  const pending: (() => void)[] = [];
  return {
    sent,
    sendOne: (payload: Buffer, settled: () => void) => {
      sent.push(payload.toString());
      pending.push(settled);
    },
    ack: () => pending.shift()?.(),
  };
}

const b = (s: string) => Buffer.from(s);

describe('joinedStream: one QoS 1 message unacknowledged, the rest joined', () => {
  test('a quick client gets every payload on its own', () => {
    const sent: string[] = [];
    const s = joinedStream((p, settled) => (sent.push(p.toString()), settled()), 100);
    for (const t of ['$TIM:1!a', '$TIM:2!b', '$TIM:3!c']) s.send(b(t));
    expect(sent).toEqual(['$TIM:1!a', '$TIM:2!b', '$TIM:3!c']);
    expect(s.waiting).toBe(0);
  });

  test('payloads made while one waits go as one message, in order, nothing lost', () => {
    const c = slowClient();
    const s = joinedStream(c.sendOne, 100);
    s.send(b('$TIM:1!a'));
    for (const t of ['$TIM:2!b', '$TIM:3!c', '$TIM:4!d']) s.send(b(t));
    expect(c.sent).toEqual(['$TIM:1!a']);
    expect(s.waiting).toBe(1);
    c.ack();
    expect(c.sent).toEqual(['$TIM:1!a', '$TIM:2!b$TIM:3!c$TIM:4!d']);
    s.send(b('$TIM:5!e'));
    c.ack();
    c.ack();
    expect(c.sent.join('')).toBe('$TIM:1!a$TIM:2!b$TIM:3!c$TIM:4!d$TIM:5!e');
    expect(s.waiting).toBe(0);
    expect(s.sent).toBe(3);
  });

  test('flush hands every waiting message over at once, before the client ends', () => {
    const c = slowClient();
    const s = joinedStream(c.sendOne, 20);
    for (let i = 0; i <= 5; i++) s.send(b(`$TIM:${i}!xx`));
    s.flush();
    expect(c.sent.join('')).toBe('$TIM:0!xx$TIM:1!xx$TIM:2!xx$TIM:3!xx$TIM:4!xx$TIM:5!xx');
    expect(s.waiting).toBe(0);
  });

  test('a joined message never exceeds the limit: the next one starts', () => {
    const c = slowClient();
    const s = joinedStream(c.sendOne, 20);
    s.send(b('$TIM:0!'));
    for (let i = 1; i <= 5; i++) s.send(b(`$TIM:${i}!xx`)); // 9 bytes each: two fit in 20
    expect(s.waiting).toBe(3);
    for (let i = 0; i < 4; i++) c.ack();
    expect(c.sent.slice(1)).toEqual(['$TIM:1!xx$TIM:2!xx', '$TIM:3!xx$TIM:4!xx', '$TIM:5!xx']);
    expect(c.sent.every((m) => m.length <= 20)).toBe(true);
  });
});
