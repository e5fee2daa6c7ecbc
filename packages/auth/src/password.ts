/**
 * Password hashes in Mosquitto 2.0's password-file format, with node:crypto only, so one
 * users file serves both the embedded broker and a Mosquitto deployment:
 *
 *   $7$<iterations>$<base64 salt>$<base64 PBKDF2-HMAC-SHA512(password, salt, iterations, 64)>
 *
 * (what `mosquitto_passwd` writes since 2.0; it uses 101 iterations and a 12-byte salt).
 * `$6$<salt>$<SHA512(password ‖ salt)>`, Mosquitto ≤ 1.6's format, is still verified so an
 * old password file keeps working, but never written. Pure apart from the random salt.
 */
import { createHash, pbkdf2Sync, randomBytes, timingSafeEqual } from 'node:crypto';

export interface HashOptions {
  /** PBKDF2 iterations; Mosquitto reads any count from the hash itself. */
  iterations: number;
  /** Salt bytes (tests pass a fixed one); default 12 random bytes, as mosquitto_passwd. */
  salt?: Buffer;
}

/**
 * 10 000 rather than mosquitto_passwd's 101: still ≈ 10 ms per check on a small board, but
 * 100 × the work for whoever steals the file. Mosquitto verifies any count.
 */
export const DEFAULT_HASH_OPTIONS: HashOptions = { iterations: 10_000 };

const KEY_BYTES = 64;
const MAX_ITERATIONS = 10_000_000;

/** A `$7$` hash of the password. */
export function hashPassword(password: string, options: Partial<HashOptions> = {}): string {
  const o = { ...DEFAULT_HASH_OPTIONS, ...options };
  if (!Number.isInteger(o.iterations) || o.iterations < 1 || o.iterations > MAX_ITERATIONS)
    throw new RangeError(`iterations must be an integer in 1–${MAX_ITERATIONS}`);
  const salt = o.salt ?? randomBytes(12);
  const key = pbkdf2Sync(password, salt, o.iterations, KEY_BYTES, 'sha512');
  return `$7$${o.iterations}$${salt.toString('base64')}$${key.toString('base64')}`;
}

/** Whether the text is a hash this module can verify (`$7$…` or `$6$…`). */
export function isPasswordHash(text: string): boolean {
  return parseHash(text) !== null;
}

interface ParsedHash {
  kind: 6 | 7;
  iterations: number;
  salt: Buffer;
  key: Buffer;
}

const B64 = /^[A-Za-z0-9+/]+={0,2}$/;

function parseHash(text: string): ParsedHash | null {
  const parts = text.split('$');
  if (parts[0] !== '') return null;
  if (parts[1] === '7' && parts.length === 5) {
    const iterations = Number(parts[2]);
    const [salt, key] = [parts[3]!, parts[4]!];
    if (!/^\d{1,8}$/.test(parts[2]!) || iterations < 1 || iterations > MAX_ITERATIONS) return null;
    if (!B64.test(salt) || !B64.test(key)) return null;
    const k = Buffer.from(key, 'base64');
    if (k.length !== KEY_BYTES) return null;
    return { kind: 7, iterations, salt: Buffer.from(salt, 'base64'), key: k };
  }
  if (parts[1] === '6' && parts.length === 4) {
    const [salt, key] = [parts[2]!, parts[3]!];
    if (!B64.test(salt) || !B64.test(key)) return null;
    const k = Buffer.from(key, 'base64');
    if (k.length !== KEY_BYTES) return null;
    return { kind: 6, iterations: 1, salt: Buffer.from(salt, 'base64'), key: k };
  }
  return null;
}

/** Whether `password` matches `hash`; false (never a throw) for a hash it cannot read. */
export function verifyPassword(password: string | Buffer, hash: string): boolean {
  const h = parseHash(hash);
  if (!h) return false;
  const pw = typeof password === 'string' ? Buffer.from(password, 'utf8') : password;
  const key =
    h.kind === 7
      ? pbkdf2Sync(pw, h.salt, h.iterations, KEY_BYTES, 'sha512')
      : createHash('sha512').update(pw).update(h.salt).digest();
  return timingSafeEqual(key, h.key);
}
