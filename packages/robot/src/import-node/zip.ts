/**
 * Reading a .zip (a zipped robot folder, or one dropped on the HUD) with fflate: every file by
 * its '/'-separated name, folders skipped. Bounded: the archive, and the sum of the sizes its
 * entries declare (a zip bomb is refused before anything is inflated).
 */
import { unzipSync } from 'fflate';

/** Largest archive read, bytes. */
export const MAX_ZIP_BYTES = 512 * 1024 * 1024;
/** Largest sum of the entries' uncompressed sizes, bytes. */
export const MAX_UNZIPPED_BYTES = 1024 * 1024 * 1024;

export function readZip(buf: Buffer, maxUnzipped = MAX_UNZIPPED_BYTES): Map<string, Uint8Array> {
  if (buf.length > MAX_ZIP_BYTES) throw new Error(`zip larger than ${MAX_ZIP_BYTES} bytes`);
  let total = 0;
  let files: Record<string, Uint8Array>;
  try {
    files = unzipSync(new Uint8Array(buf.buffer, buf.byteOffset, buf.length), {
      filter: (f) => {
        if (f.name.endsWith('/')) return false;
        total += f.originalSize;
        if (total > maxUnzipped)
          throw new Error(`the files in this zip unpack to more than ${maxUnzipped} bytes`);
        return true;
      },
    });
  } catch (err) {
    const why = err instanceof Error ? err.message : String(err);
    throw new Error(/unpack to more/.test(why) ? why : `not a readable zip file (${why})`, {
      cause: err,
    });
  }
  return new Map(Object.entries(files).map(([name, data]) => [name.replace(/\\/g, '/'), data]));
}
