import { describe, expect, it } from 'vitest';
import { createFlvH264Reader, nalTypes, type AccessUnit } from '../src/index.ts';
import { feedings, fromHex, toHex } from './hex.ts';
import vectors from './vectors/flv-h264.json' with { type: 'json' };

interface Vector {
  name: string;
  chunks: string[];
  units: { data: string; key: boolean; timestampMs: number }[];
  errors: string[];
  maxTagBytes?: number;
}

function run(chunks: Uint8Array[], maxTagBytes?: number) {
  const units: { data: string; key: boolean; timestampMs: number }[] = [];
  const errors: string[] = [];
  const r = createFlvH264Reader({
    onAccessUnit: (au: AccessUnit) => units.push({ ...au, data: toHex(au.data) }),
    onError: (e) => errors.push(e.kind),
    ...(maxTagBytes ? { maxTagBytes } : {}),
  });
  for (const c of chunks) r.feed(c);
  r.flush();
  return { units, errors };
}

describe('FLV → H.264 access units, fed every way', () => {
  for (const v of vectors as Vector[]) {
    it(v.name, () => {
      for (const [how, chunks] of feedings(v.chunks.map(fromHex)))
        expect(run(chunks, v.maxTagBytes), how).toEqual({ units: v.units, errors: v.errors });
    });
  }
});

describe('FLV reader', () => {
  it('a key frame carries SPS, PPS and its IDR slice in Annex B', () => {
    const v = (vectors as Vector[])[0]!;
    const { units } = run(v.chunks.map(fromHex));
    expect(nalTypes(fromHex(units[0]!.data))).toEqual([7, 8, 6, 5]);
    expect(nalTypes(fromHex(units[1]!.data))).toEqual([1]);
  });

  it('reset() starts a new stream: header and configuration again', () => {
    const v = (vectors as Vector[])[0]!;
    const whole = fromHex(v.chunks[0]!);
    const units: AccessUnit[] = [];
    const errors: string[] = [];
    const r = createFlvH264Reader({
      onAccessUnit: (u) => units.push(u),
      onError: (e) => errors.push(e.kind),
    });
    r.feed(whole.subarray(0, 40));
    r.reset();
    expect(r.config).toBeNull();
    r.feed(whole);
    expect(units).toHaveLength(3);
    expect(errors).toEqual([]);
  });
});
