import { describe, expect, it } from 'vitest';
import { SegmentsAhead } from '../src/core/replay/segmentsAhead.ts';
import { fetchSegment } from '../src/ui/panels/History/cameraSegmentsApi.ts';

const SEGMENTS = [
  { name: 'a', startMs: 1000, endMs: 3000 },
  { name: 'b', startMs: 3000, endMs: 5000 },
  { name: 'c', startMs: 8000, endMs: 9500 },
];

/** A loader that counts each name it fetched; `fail` names reject (once each). */
function loader(fail: string[] = []) {
  const fetched: string[] = [];
  const load = (name: string) => {
    fetched.push(name);
    const i = fail.indexOf(name);
    if (i >= 0) {
      fail.splice(i, 1);
      return Promise.reject(new Error(`segment ${name}: HTTP 503`));
    }
    return Promise.resolve(`bytes of ${name}`);
  };
  return { fetched, load };
}

describe('SegmentsAhead: the replayed segment and the one after it', () => {
  it('asking for a segment fetches it and the next, so the boundary finds the next one there', async () => {
    const l = loader();
    const ahead = new SegmentsAhead(l.load);
    expect(await ahead.get(SEGMENTS, 'a')).toBe('bytes of a');
    expect(l.fetched).toEqual(['a', 'b']);
    // playback crosses into b: no new fetch of b, c is fetched ahead, a is let go
    expect(await ahead.get(SEGMENTS, 'b')).toBe('bytes of b');
    expect(l.fetched).toEqual(['a', 'b', 'c']);
    expect(ahead.names()).toEqual(['b', 'c']);
  });

  it('holds one ahead at most; the last segment has none; a scrub back fetches again', async () => {
    const l = loader();
    const ahead = new SegmentsAhead(l.load);
    await ahead.get(SEGMENTS, 'c');
    expect(ahead.names()).toEqual(['c']);
    await ahead.get(SEGMENTS, 'a');
    expect(ahead.names()).toEqual(['a', 'b']);
    expect(l.fetched).toEqual(['c', 'a', 'b']);
    // a name not in the list (a list answered later) is still fetched, alone
    await ahead.get(SEGMENTS, 'z');
    expect(ahead.names()).toEqual(['z']);
  });

  it('a failed fetch is told to the asker and tried again on the next ask', async () => {
    const l = loader(['b']);
    const ahead = new SegmentsAhead(l.load);
    await ahead.get(SEGMENTS, 'a'); // b's fetch ahead fails: no one asked for it yet
    await Promise.resolve();
    expect(ahead.names()).toEqual(['a']);
    expect(await ahead.get(SEGMENTS, 'b')).toBe('bytes of b');
    expect(l.fetched).toEqual(['a', 'b', 'b', 'c']);
    const m = loader(['a']);
    await expect(new SegmentsAhead(m.load).get(SEGMENTS, 'a')).rejects.toThrow(
      'segment a: HTTP 503',
    );
  });

  it("fetches the segment ahead with the page's log-in, as the one asked for", async () => {
    const asked: { url: string; headers: unknown }[] = [];
    const source = {
      base: '/api',
      headers: { authorization: 'Basic eDp5' },
      fetch: (url: string, init?: RequestInit) => {
        asked.push({ url, headers: init?.headers });
        return Promise.resolve(new Response(new Uint8Array([1, 2, 3])));
      },
    };
    const ahead = new SegmentsAhead((name) => fetchSegment(source, 'arm1', 'front', name));
    expect((await ahead.get(SEGMENTS, 'a')).size).toBe(3);
    expect(asked.map((a) => a.url)).toEqual([
      '/api/arms/arm1/cameras/front/segments/a',
      '/api/arms/arm1/cameras/front/segments/b',
    ]);
    for (const a of asked) expect(a.headers).toMatchObject({ authorization: 'Basic eDp5' });
  });
});
