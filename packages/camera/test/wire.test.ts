import { describe, expect, it } from 'vitest';
import {
  codecOfAccessUnit,
  decodeH264Message,
  drawTimeStripe,
  encodeH264Message,
  h264CodecString,
  isKeyAccessUnit,
  nalTypes,
  readTimeStripe,
  timeStripeFilter,
  timeStripeLayout,
} from '../src/client.ts';
import { fromHex } from './hex.ts';

describe('h264-ws message', () => {
  it('round-trips, header big-endian at fixed offsets', () => {
    const data = fromHex('0000000167420C');
    const bytes = encodeH264Message({
      key: true,
      replay: false,
      timestampMs: 1795490653745.5,
      seq: 7,
      data,
    });
    expect([...bytes.subarray(0, 4)]).toEqual([1, 1, 0, 16]);
    expect(new DataView(bytes.buffer).getFloat64(4)).toBe(1795490653745.5);
    expect(new DataView(bytes.buffer).getUint32(12)).toBe(7);
    const back = decodeH264Message(bytes.buffer as ArrayBuffer);
    expect(back).toEqual({
      ok: true,
      message: { key: true, replay: false, timestampMs: 1795490653745.5, seq: 7, data },
    });
  });

  it('a longer header from a later version is skipped by its length', () => {
    const bytes = encodeH264Message({
      key: false,
      replay: true,
      timestampMs: 1,
      seq: 2,
      data: fromHex('AA'),
    });
    const longer = new Uint8Array(bytes.length + 4);
    longer.set(bytes.subarray(0, 16));
    longer.set(bytes.subarray(16), 20);
    longer[3] = 20;
    const back = decodeH264Message(longer);
    expect(back.ok && [...back.message.data]).toEqual([0xaa]);
    expect(back.ok && back.message.replay).toBe(true);
  });

  it('says why a message is not one', () => {
    expect(decodeH264Message(new Uint8Array(3))).toEqual({ ok: false, error: 'too-short' });
    expect(decodeH264Message(Uint8Array.of(2, 0, 0, 16))).toEqual({
      ok: false,
      error: 'bad-version',
    });
    expect(decodeH264Message(Uint8Array.of(1, 0, 0, 4))).toEqual({
      ok: false,
      error: 'bad-header-length',
    });
    expect(decodeH264Message(Uint8Array.of(1, 0, 0, 16, 0))).toEqual({
      ok: false,
      error: 'too-short',
    });
  });
});

describe('NAL units', () => {
  const key = fromHex(
    '00000001' + '6742C01EDA' + '000001' + '68CE3C80' + '00000001' + '65888400' + '0000',
  );
  it('cuts an access unit at 3- and 4-byte start codes', () => {
    expect(nalTypes(key)).toEqual([7, 8, 5]);
    expect(isKeyAccessUnit(key)).toBe(true);
    expect(isKeyAccessUnit(fromHex('00000001419A'))).toBe(false);
  });
  it('gives the WebCodecs codec string of the SPS', () => {
    expect(codecOfAccessUnit(key)).toBe('avc1.42C01E');
    expect(h264CodecString(fromHex('6742E01E'))).toBe('avc1.42E01E');
    expect(h264CodecString(fromHex('68CE'))).toBeNull();
  });
});

describe('time stripe', () => {
  it('reads back what was drawn, at 640×480 and 1280×720', () => {
    for (const [w, h] of [
      [640, 480],
      [1280, 720],
    ] as const) {
      const luma = new Uint8Array(w * h).fill(128);
      for (const t of [0, 1, 1795490653745, 2 ** 44 - 1]) {
        drawTimeStripe(luma, w, h, t);
        expect(readTimeStripe(luma, w, h), `${w}×${h} ${t}`).toBe(t);
      }
    }
  });
  it('reads RGBA (stride 4) and says null where there is no stripe', () => {
    const w = 640,
      h = 480;
    const luma = new Uint8Array(w * h);
    drawTimeStripe(luma, w, h, 1234567);
    const rgba = new Uint8ClampedArray(w * h * 4);
    luma.forEach((v, i) => rgba.fill(v, i * 4, i * 4 + 4));
    expect(readTimeStripe(rgba, w, h, 4)).toBe(1234567);
    expect(readTimeStripe(new Uint8Array(w * h).fill(200), w, h)).toBeNull();
  });
  it('the ffmpeg filter draws one box per bit, each switched by its bit of t', () => {
    const f = timeStripeFilter(640, 480);
    const l = timeStripeLayout(640, 480);
    expect(f.startsWith('settb=1/1000,setpts=RTCTIME/1000,')).toBe(true);
    expect(f.match(/enable=/g)).toHaveLength(l.bits);
    expect(f).toContain(`:enable='mod(floor((t*1000+0.5)/1),2)'`);
  });
});
