/** The Cartesian panel's text fields → numbers. Pure. */
export interface TargetFields {
  x: string;
  y: string;
  z: string;
  /** Blank = let the controller choose (no α in `$KMS`). */
  pitch: string;
}

export type ParsedTarget =
  | { ok: true; x: number; y: number; z: number; pitch: number | undefined }
  | { ok: false; error: string };

/** Largest |coordinate| accepted, mm (far beyond the arm; keeps `$KMS` in range). */
const LIMIT_MM = 10_000;

export function parseTarget(f: TargetFields): ParsedTarget {
  const nums: number[] = [];
  for (const key of ['x', 'y', 'z'] as const) {
    const text = f[key].trim();
    const v = Number(text);
    if (text === '' || !Number.isFinite(v))
      return { ok: false, error: `${key.toUpperCase()} must be a number (mm).` };
    if (Math.abs(v) > LIMIT_MM)
      return { ok: false, error: `${key.toUpperCase()} must be within ±${LIMIT_MM} mm.` };
    nums.push(v);
  }
  const p = f.pitch.trim();
  let pitch: number | undefined;
  if (p !== '') {
    pitch = Number(p);
    if (!Number.isFinite(pitch) || pitch < -90 || pitch > 90)
      return { ok: false, error: 'Pitch must be between −90 and 90 degrees, or blank.' };
  }
  return { ok: true, x: nums[0]!, y: nums[1]!, z: nums[2]!, pitch };
}
