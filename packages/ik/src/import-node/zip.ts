/**
 * A small reader of .zip archives (stored and deflated entries, no encryption, no ZIP64), enough
 * for a robot folder zipped by any common tool: the central directory gives each file's name,
 * method and sizes; the data follows the local header. Names are '/'-separated; folders skipped.
 */
import zlib from 'node:zlib';

/** Largest archive read, bytes. */
export const MAX_ZIP_BYTES = 512 * 1024 * 1024;

export function readZip(buf: Buffer): Map<string, Uint8Array> {
  if (buf.length > MAX_ZIP_BYTES) throw new Error(`zip larger than ${MAX_ZIP_BYTES} bytes`);
  let eocd = -1;
  for (let i = buf.length - 22; i >= Math.max(0, buf.length - 22 - 65535); i--)
    if (buf.readUInt32LE(i) === 0x06054b50) {
      eocd = i;
      break;
    }
  if (eocd < 0) throw new Error('not a zip file (no end of central directory)');
  const count = buf.readUInt16LE(eocd + 10);
  let p = buf.readUInt32LE(eocd + 16);
  const files = new Map<string, Uint8Array>();
  for (let k = 0; k < count; k++) {
    if (buf.readUInt32LE(p) !== 0x02014b50) throw new Error('corrupt zip central directory');
    const flags = buf.readUInt16LE(p + 8);
    const method = buf.readUInt16LE(p + 10);
    const compressed = buf.readUInt32LE(p + 20);
    const size = buf.readUInt32LE(p + 24);
    const nameLen = buf.readUInt16LE(p + 28);
    const extraLen = buf.readUInt16LE(p + 30);
    const commentLen = buf.readUInt16LE(p + 32);
    const local = buf.readUInt32LE(p + 42);
    const name = buf.toString('utf8', p + 46, p + 46 + nameLen);
    p += 46 + nameLen + extraLen + commentLen;
    if (name.endsWith('/')) continue;
    if (flags & 1) throw new Error(`${name}: encrypted zip entries are not supported`);
    if (buf.readUInt32LE(local) !== 0x04034b50) throw new Error(`${name}: corrupt local header`);
    const start = local + 30 + buf.readUInt16LE(local + 26) + buf.readUInt16LE(local + 28);
    const raw = buf.subarray(start, start + compressed);
    let data: Uint8Array;
    if (method === 0) data = raw;
    else if (method === 8) data = zlib.inflateRawSync(raw, { maxOutputLength: Math.max(size, 1) });
    else throw new Error(`${name}: zip method ${method} is not supported (stored or deflate)`);
    if (data.length !== size) throw new Error(`${name}: size ${data.length}, expected ${size}`);
    files.set(name.replace(/\\/g, '/'), data);
  }
  return files;
}
