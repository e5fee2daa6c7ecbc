/**
 * The CRC-16 of Dynamixel Protocol 2.0 as ROBOTIS specifies it: polynomial 0x8005, not
 * reflected, initial value 0, no final XOR (the catalogue's CRC-16/UMTS, alias BUYPASS),
 * computed over every byte of the packet on the wire, header and stuffing included, up to the
 * CRC itself. The table is built once, at load.
 */
const TABLE = new Uint16Array(256);
for (let n = 0; n < 256; n++) {
  let crc = n << 8;
  for (let bit = 0; bit < 8; bit++)
    crc = crc & 0x8000 ? ((crc << 1) ^ 0x8005) & 0xffff : (crc << 1) & 0xffff;
  TABLE[n] = crc;
}

/** CRC-16 of `bytes[start, end)`, continuing from `crc` (0 for a fresh packet). */
export function crc16(bytes: Uint8Array, start = 0, end = bytes.length, crc = 0): number {
  for (let i = start; i < end; i++)
    crc = ((crc << 8) ^ TABLE[((crc >> 8) ^ bytes[i]!) & 0xff]!) & 0xffff;
  return crc;
}
