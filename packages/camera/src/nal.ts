/**
 * H.264 Annex B helpers, browser-safe: the NAL units of an access unit (cut at its start codes),
 * and the WebCodecs codec string of an SPS. Used by the server (to check what it sends), by the
 * tests and by the HUD (to configure its `VideoDecoder`).
 */

/** NAL unit types armtwin looks at (ITU-T H.264 Table 7-1). */
export const NAL = {
  slice: 1,
  idr: 5,
  sei: 6,
  sps: 7,
  pps: 8,
  aud: 9,
} as const;

export interface NalUnit {
  /** nal_unit_type, 0–31. */
  type: number;
  /** The unit without its start code, a view into the access unit. */
  data: Uint8Array;
}

/**
 * The NAL units of one Annex B access unit (start codes `00 00 01` or `00 00 00 01`). Bytes
 * before the first start code are skipped; a unit's trailing zero bytes belong to the next
 * start code.
 */
export function nalUnits(au: Uint8Array): NalUnit[] {
  const starts: { at: number; len: number }[] = [];
  for (let i = 0; i + 2 < au.length; i++) {
    if (au[i] === 0 && au[i + 1] === 0 && au[i + 2] === 1) {
      const four = i > 0 && au[i - 1] === 0;
      starts.push({ at: four ? i - 1 : i, len: four ? 4 : 3 });
      i += 2;
    }
  }
  const units: NalUnit[] = [];
  for (let k = 0; k < starts.length; k++) {
    const begin = starts[k]!.at + starts[k]!.len;
    let end = k + 1 < starts.length ? starts[k + 1]!.at : au.length;
    while (end > begin && au[end - 1] === 0) end--;
    if (end > begin) units.push({ type: au[begin]! & 0x1f, data: au.subarray(begin, end) });
  }
  return units;
}

/** The types of an access unit's NAL units, in order. */
export const nalTypes = (au: Uint8Array): number[] => nalUnits(au).map((u) => u.type);

/** Whether an access unit holds an IDR slice. */
export const isKeyAccessUnit = (au: Uint8Array): boolean =>
  nalUnits(au).some((u) => u.type === NAL.idr);

const hex2 = (n: number) => n.toString(16).toUpperCase().padStart(2, '0');

/** `avc1.PPCCLL` from an SPS NAL unit (profile_idc, constraint flags, level_idc), or null. */
export function h264CodecString(sps: Uint8Array): string | null {
  if (sps.length < 4 || (sps[0]! & 0x1f) !== NAL.sps) return null;
  return `avc1.${hex2(sps[1]!)}${hex2(sps[2]!)}${hex2(sps[3]!)}`;
}

/** The codec string of an access unit's SPS (a key frame's), or null when it has none. */
export function codecOfAccessUnit(au: Uint8Array): string | null {
  const sps = nalUnits(au).find((u) => u.type === NAL.sps);
  return sps ? h264CodecString(sps.data) : null;
}
