import { describe, expect, it } from 'vitest';
import { createMultipartParser, multipartBoundary, type MultipartPart } from '../src/client.ts';
import { feedings, fromHex, toHex } from './hex.ts';
import vectors from './vectors/multipart-parser.json' with { type: 'json' };

interface Vector {
  name: string;
  boundary?: string;
  chunks: string[];
  parts: { headers: Record<string, string>; body: string }[];
  errors: string[];
  maxPartBytes?: number;
  maxHeaderBytes?: number;
}

function run(v: Vector, chunks: Uint8Array[]) {
  const parts: { headers: Record<string, string>; body: string }[] = [];
  const errors: string[] = [];
  const p = createMultipartParser({
    boundary: v.boundary ?? 'armtwin-frame',
    onPart: (part: MultipartPart) => parts.push({ headers: part.headers, body: toHex(part.body) }),
    onError: (e) => errors.push(e.kind),
    ...(v.maxPartBytes ? { maxPartBytes: v.maxPartBytes } : {}),
    ...(v.maxHeaderBytes ? { maxHeaderBytes: v.maxHeaderBytes } : {}),
  });
  for (const c of chunks) p.feed(c);
  p.flush();
  return { parts, errors };
}

describe('multipart parser vectors, fed every way', () => {
  for (const v of vectors as Vector[]) {
    it(v.name, () => {
      for (const [how, chunks] of feedings(v.chunks.map(fromHex)))
        expect(run(v, chunks), how).toEqual({ parts: v.parts, errors: v.errors });
    });
  }
});

describe('multipart parser', () => {
  it('hands out a part with Content-Length as soon as its body is in, before any boundary', () => {
    const bodies: Uint8Array[] = [];
    const p = createMultipartParser({ boundary: 'b', onPart: (x) => bodies.push(x.body) });
    p.feed(new TextEncoder().encode('--b\r\nContent-Length: 3\r\n\r\nabc'));
    expect(bodies.map((b) => new TextDecoder().decode(b))).toEqual(['abc']);
  });

  it('reads the boundary of a Content-Type header', () => {
    expect(multipartBoundary('multipart/x-mixed-replace; boundary=armtwin-frame')).toBe(
      'armtwin-frame',
    );
    expect(multipartBoundary('multipart/x-mixed-replace;boundary="a b"')).toBe('a b');
    expect(multipartBoundary('image/jpeg')).toBeNull();
  });
});
