import { describe, expect, it } from 'vitest';
import { fetchSegment, listSegments } from '../src/ui/panels/History/cameraSegmentsApi.ts';

const range = { start: Date.UTC(2026, 0, 1, 12), stop: Date.UTC(2026, 0, 1, 12, 5) };

describe('the camera segments client', () => {
  it("asks for the range in ISO times with the login, and keeps each segment's times", async () => {
    const asked: { url: string; headers: unknown }[] = [];
    const l = await listSegments(
      {
        base: '/api/',
        headers: { authorization: 'Basic eDp5' },
        fetch: (url, init) => {
          asked.push({ url, headers: init?.headers });
          const segments = [{ name: 'a.mp4', startMs: 1, endMs: 2, bytes: 9, url: '/x' }];
          return Promise.resolve(new Response(JSON.stringify({ ok: true, segments })));
        },
      },
      'arm1',
      'front',
      range,
    );
    expect(l).toEqual({ ok: true, data: [{ name: 'a.mp4', startMs: 1, endMs: 2 }] });
    expect(asked[0]!.url).toBe(
      '/api/arms/arm1/cameras/front/segments?from=2026-01-01T12%3A00%3A00.000Z&to=2026-01-01T12%3A05%3A00.000Z',
    );
    expect(asked[0]!.headers).toMatchObject({ authorization: 'Basic eDp5' });
  });

  it('says why when the middleware does not record, or cannot be reached', async () => {
    const off = await listSegments(
      {
        base: '/api',
        fetch: () =>
          Promise.resolve(
            new Response(JSON.stringify({ ok: false, errors: ['CAMERA_RECORD is off'] }), {
              status: 503,
            }),
          ),
      },
      'arm1',
      'front',
      range,
    );
    expect(off).toEqual({
      ok: false,
      error: 'The camera recordings of front are not available: CAMERA_RECORD is off',
    });
    const down = await listSegments(
      { base: '/api', fetch: () => Promise.reject(new TypeError('Failed to fetch')) },
      'arm1',
      'front',
      range,
    );
    expect(down.ok || down.error).toMatch(/unreachable: TypeError: Failed to fetch/);
  });

  it('fetches one segment whole, and a missing one is an error', async () => {
    const o = {
      base: '/api',
      fetch: (url: string) =>
        Promise.resolve(
          url.endsWith('/segments/a.mp4')
            ? new Response(new Uint8Array([1, 2, 3]))
            : new Response('{}', { status: 404 }),
        ),
    };
    expect((await fetchSegment(o, 'arm1', 'front', 'a.mp4')).size).toBe(3);
    await expect(fetchSegment(o, 'arm1', 'front', 'b.mp4')).rejects.toThrow('HTTP 404');
  });
});
