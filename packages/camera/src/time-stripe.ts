/**
 * A clock burned into the test source, machine-readable, browser-safe: a row of black and white
 * blocks along the bottom of each frame holding the wall-clock time (epoch ms) at which ffmpeg
 * produced the frame. A benchmark reads it back from the pixels of the frame a page shows and
 * subtracts it from its own clock: glass-to-glass latency without OCR and without fonts.
 *
 * Layout (`timeStripeLayout`): a black band `blockH` px high at the bottom; in it, from `x0`,
 * `TIME_STRIPE_BITS + 2` blocks `blockW` px wide: a white guard, the bits most significant first
 * (white = 1), a black guard. 44 bits of epoch ms last until the year 2527.
 *
 * ffmpeg side (`timeStripeFilter`): `setpts` stamps each frame with `RTCTIME` (ms time base),
 * then one `drawbox` per bit is switched on per frame by its timeline expression on `t`, so the
 * whole frame carries one instant (per-pixel `geq` would be slower and could straddle a ms).
 */

export const TIME_STRIPE_BITS = 44;

/** Filters that stamp each frame with the wall clock as it passes, epoch ms in a 1 ms time base. */
export const WALL_CLOCK_PTS = ['settb=1/1000', 'setpts=RTCTIME/1000'] as const;

export interface TimeStripeLayout {
  bits: number;
  blockW: number;
  blockH: number;
  /** Left edge of the white guard block. */
  x0: number;
  /** Top of the band. */
  y0: number;
}

/** Where the blocks are in a frame of this size. */
export function timeStripeLayout(width: number, height: number): TimeStripeLayout {
  const blocks = TIME_STRIPE_BITS + 2;
  const blockW = Math.floor(width / (blocks + 2));
  const blockH = Math.max(8, Math.min(24, Math.floor(height / 30)));
  if (blockW < 4 || height < blockH * 4)
    throw new RangeError(`a ${width}×${height} frame is too small for the time stripe`);
  return {
    bits: TIME_STRIPE_BITS,
    blockW,
    blockH,
    x0: Math.floor((width - blocks * blockW) / 2),
    y0: height - blockH,
  };
}

/**
 * The ffmpeg filter chain (for `-vf` or inside a `-filter_complex` chain) that stamps the frames
 * with the wall clock and draws the stripe. It leaves the frames' pts in epoch ms.
 */
export function timeStripeFilter(width: number, height: number): string {
  const l = timeStripeLayout(width, height);
  const box = (x: number, w: number, color: string) =>
    `drawbox=x=${x}:y=${l.y0}:w=${w}:h=${l.blockH}:color=${color}:t=fill`;
  const filters = [...WALL_CLOCK_PTS, box(0, width, 'black'), box(l.x0, l.blockW, 'white')];
  for (let i = 0; i < l.bits; i++) {
    const weight = 2 ** (l.bits - 1 - i);
    // t is in s; +0.5 ms rounds away the float error of t*1000 before the bit is taken.
    filters.push(
      `${box(l.x0 + (i + 1) * l.blockW, l.blockW, 'white')}:enable='mod(floor((t*1000+0.5)/${weight}),2)'`,
    );
  }
  return filters.join(',');
}

/**
 * Reads the stripe from a frame's luma plane (one byte per pixel, rows of `width`, as
 * `ffmpeg -pix_fmt gray` or the R channel of an RGBA canvas with `stride` 4). Returns the epoch
 * ms, or null when the guards are not where they belong (no stripe, or a mangled one).
 */
export function readTimeStripe(
  pixels: Uint8Array | Uint8ClampedArray,
  width: number,
  height: number,
  stride = 1,
): number | null {
  const l = timeStripeLayout(width, height);
  const level = (block: number): number => {
    // The mean of the block's middle half: compression smears the edges.
    const x1 = l.x0 + block * l.blockW + Math.floor(l.blockW / 4);
    const x2 = l.x0 + (block + 1) * l.blockW - Math.floor(l.blockW / 4);
    const y1 = l.y0 + Math.floor(l.blockH / 4);
    const y2 = l.y0 + l.blockH - Math.floor(l.blockH / 4);
    let sum = 0;
    let n = 0;
    for (let y = y1; y < y2; y++)
      for (let x = x1; x < x2; x++) {
        sum += pixels[(y * width + x) * stride] ?? 0;
        n++;
      }
    return n ? sum / n : 0;
  };
  if (level(0) < 160 || level(l.bits + 1) > 96) return null;
  let value = 0;
  for (let i = 0; i < l.bits; i++) value = value * 2 + (level(i + 1) >= 128 ? 1 : 0);
  return value;
}

/** Writes the stripe of `epochMs` into a luma plane: the reference the tests check the reader with. */
export function drawTimeStripe(
  pixels: Uint8Array,
  width: number,
  height: number,
  epochMs: number,
): void {
  const l = timeStripeLayout(width, height);
  const fill = (x: number, w: number, v: number) => {
    for (let y = l.y0; y < l.y0 + l.blockH; y++) pixels.fill(v, y * width + x, y * width + x + w);
  };
  fill(0, width, 16);
  fill(l.x0, l.blockW, 235);
  for (let i = 0; i < l.bits; i++) {
    const bit = Math.floor(epochMs / 2 ** (l.bits - 1 - i)) % 2;
    if (bit) fill(l.x0 + (i + 1) * l.blockW, l.blockW, 235);
  }
}
