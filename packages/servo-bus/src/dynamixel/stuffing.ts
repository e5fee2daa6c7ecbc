/**
 * Byte stuffing of Dynamixel Protocol 2.0: inside a packet's body (instruction, error and
 * parameters), wherever `FF FF FD` occurs an extra `FD` follows it on the wire, so the header
 * `FF FF FD 00` cannot appear inside a packet. The length field counts the stuffed bytes.
 */

/** The body as sent: `FF FF FD` becomes `FF FF FD FD`. */
export function stuff(body: Uint8Array): Uint8Array {
  const out: number[] = [];
  for (let i = 0; i < body.length; i++) {
    const b = body[i]!;
    out.push(b);
    if (b === 0xfd && i >= 2 && body[i - 1] === 0xff && body[i - 2] === 0xff) out.push(0xfd);
  }
  return out.length === body.length ? body : Uint8Array.from(out);
}

/** The body as meant: the `FD` after each `FF FF FD` on the wire is dropped. */
export function unstuff(wire: Uint8Array): Uint8Array {
  const out: number[] = [];
  for (let i = 0; i < wire.length; i++) {
    const b = wire[i]!;
    out.push(b);
    if (
      b === 0xfd &&
      i >= 2 &&
      wire[i - 1] === 0xff &&
      wire[i - 2] === 0xff &&
      wire[i + 1] === 0xfd
    )
      i++;
  }
  return out.length === wire.length ? wire : Uint8Array.from(out);
}
