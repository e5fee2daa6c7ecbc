import { describe, expect, it } from 'vitest';
import { createReader, type Frame, type Group, type ReaderError } from '../src/index.ts';
import vectors from './vectors/reader.json' with { type: 'json' };

interface Vector {
  name: string;
  chunks: string[];
  events: unknown[];
  errors: string[];
}

function run(chunks: string[]) {
  const events: (Frame | Group)[] = [];
  const errors: ReaderError[] = [];
  const reader = createReader({
    onFrame: (f) => events.push(f),
    onGroup: (g) => events.push(g),
    onError: (e) => errors.push(e),
  });
  for (const chunk of chunks) reader.feed(chunk);
  reader.flush();
  return { events, errors: errors.map((e) => e.kind) };
}

describe('reader test vectors', () => {
  for (const v of vectors as Vector[]) {
    const whole = v.chunks.join('');
    it(`${v.name}: as given`, () => {
      expect(run(v.chunks)).toEqual({ events: v.events, errors: v.errors });
    });
    it(`${v.name}: split at every byte offset`, () => {
      for (let cut = 0; cut <= whole.length; cut++) {
        expect(run([whole.slice(0, cut), whole.slice(cut)]), `cut at ${cut}`).toEqual({
          events: v.events,
          errors: v.errors,
        });
      }
    });
    it(`${v.name}: one byte at a time, as bytes`, () => {
      const bytes = new TextEncoder().encode(whole);
      const chunks = [...bytes].map((b) => String.fromCharCode(b));
      expect(run(chunks)).toEqual({ events: v.events, errors: v.errors });
    });
  }
});

describe('reader API', () => {
  it('reports junk ending in "!" at its "!", before any later input arrives', () => {
    const errors: ReaderError[] = [];
    const reader = createReader({ onError: (e) => errors.push(e) });
    reader.feed('hello ');
    expect(errors).toEqual([]);
    reader.feed('world!');
    expect(errors).toEqual([
      { kind: 'junk', message: 'bytes between frames that are not a frame', text: 'hello world!' },
    ]);
  });

  it('accepts Uint8Array chunks', () => {
    const frames: Frame[] = [];
    const reader = createReader({ onFrame: (f) => frames.push(f) });
    reader.feed(new TextEncoder().encode('#000P15'));
    reader.feed(new TextEncoder().encode('00!'));
    expect(frames).toEqual([{ type: 'position', id: 0, pwm: 1500 }]);
  });

  it('clearStamp stops stamping until the next $TIM', () => {
    const frames: Frame[] = [];
    const reader = createReader({ onFrame: (f) => frames.push(f) });
    reader.feed('$TIM:5!#000P1500!');
    reader.clearStamp();
    reader.feed('#000P1501!');
    expect(frames.at(-1)).toEqual({ type: 'position', id: 0, pwm: 1501 });
  });

  it('holds at most one partial frame and reports errors with a reason', () => {
    const errors: ReaderError[] = [];
    const reader = createReader({ onError: (e) => errors.push(e) });
    reader.feed('#000P1500T99999!#000P15');
    expect(reader.bufferedBytes).toBe(7);
    expect(errors[0]).toMatchObject({ kind: 'out-of-range', message: 'ms 99999 outside 0–9999' });
    reader.reset();
    expect(reader.bufferedBytes).toBe(0);
  });

  it('cuts a group that grows past its bound', () => {
    const groups: Group[] = [];
    const errors: ReaderError[] = [];
    const reader = createReader({
      maxGroupFrames: 2,
      onGroup: (g) => groups.push(g),
      onError: (e) => errors.push(e),
    });
    reader.feed('{#000P1500!#001P1500!#002P1500!}');
    expect(groups).toHaveLength(1);
    expect(groups[0]!.frames).toHaveLength(2);
    expect(errors.map((e) => e.kind)).toEqual(['unterminated-group', 'unexpected-group-end']);
  });
});
