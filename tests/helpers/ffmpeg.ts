/**
 * Decoding with the real ffmpeg (Debian's) in a test: pipes bytes in, gives its output, its
 * error text and exit code; killed after 20 s.
 */
import { spawn } from 'node:child_process';

/** Runs ffmpeg over `input` (stdin) and returns its stdout and stderr. */
export function ffmpeg(
  args: string[],
  input: Uint8Array,
): Promise<{ out: Buffer; err: string; code: number | null }> {
  return new Promise((resolve, reject) => {
    const child = spawn('ffmpeg', ['-hide_banner', '-nostdin', '-loglevel', 'error', ...args], {
      stdio: ['pipe', 'pipe', 'pipe'],
    });
    const timer = setTimeout(() => child.kill('SIGKILL'), 20_000);
    const out: Buffer[] = [];
    let err = '';
    child.stdout.on('data', (d: Buffer) => out.push(d));
    child.stderr.on('data', (d: Buffer) => (err += d.toString()));
    child.on('error', reject);
    child.on('close', (code) => {
      clearTimeout(timer);
      resolve({ out: Buffer.concat(out), err, code });
    });
    child.stdin.on('error', () => {});
    child.stdin.end(input);
  });
}

/** A JPEG decoded to 8-bit gray pixels (row after row), for reading its time stripe. */
export const gray = (jpeg: Uint8Array) =>
  ffmpeg(['-f', 'mjpeg', '-i', 'pipe:0', '-f', 'rawvideo', '-pix_fmt', 'gray', 'pipe:1'], jpeg);
