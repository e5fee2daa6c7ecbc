/**
 * The camera side of the camera bench (../camera.ts): one `armtwin camera --kinds <kind>
 * --no-announce` per stream as a tracked child (./proc.ts), on 127.0.0.1 with a free port, and
 * the CPU of its process tree (node and the ffmpeg it runs), utime + stime from /proc.
 */
import path from 'node:path';
import type { CameraKind } from '@armtwin/camera/announcement';
import { cpuSeconds, descendants, spawnChild, type Child } from './proc.ts';
import { REPO } from './stack.ts';

const ARMTWIN = path.join(REPO, 'apps', 'cli', 'bin', 'armtwin.mjs');

/** One camera server: `armtwin camera` serving one kind of one test-source stream. */
export interface CameraServer {
  child: Child;
  camId: string;
  label: string;
  url: string;
}

export async function startCameraServer(o: {
  armId: string;
  kind: CameraKind;
  camId: string;
  label: string;
  width: number;
  height: number;
  fps: number;
  logFile: string;
}): Promise<CameraServer> {
  const { kind, camId, label, logFile } = o;
  const child = spawnChild(
    process.execPath,
    [
      ARMTWIN,
      'camera',
      ...['--arm', o.armId, '--name', camId, '--label', label, '--source', 'testsrc'],
      ...['--kinds', kind, '--size', `${o.width}x${o.height}`, '--fps', String(o.fps)],
      ...['--host', '127.0.0.1', '--port', '0', '--no-announce'],
    ],
    { cwd: REPO, logFile, stdout: 'pipe', env: { ...process.env, LOG_LEVEL: 'warn' } },
  );
  // It prints its MJPEG URL (http://127.0.0.1:PORT/camera/<camId>.mjpeg) once it listens.
  const first = await new Promise<string>((resolve, reject) => {
    let buf = '';
    const timer = setTimeout(
      () => reject(new Error(`armtwin camera: no URL (${logFile})`)),
      30_000,
    );
    child.proc.stdout?.on('data', (d: Buffer) => {
      buf += d.toString();
      if (buf.includes('\n')) {
        clearTimeout(timer);
        resolve(buf.slice(0, buf.indexOf('\n')).trim());
      }
    });
    void child.exited.then(() => reject(new Error(`armtwin camera exited (${logFile})`)));
  });
  const base = first.replace(/\/camera\/.*$/, '');
  const url =
    kind === 'mjpeg'
      ? `${base}/camera/${camId}.mjpeg`
      : `${base.replace(/^http/, 'ws')}/camera/${camId}.h264`;
  return { child, camId, label, url };
}

/** CPU of a process tree (the camera server and its ffmpeg) over a window, by pid. */
export function treeMeter(pid: number) {
  const pids = () => [pid, ...descendants(pid)];
  let c0 = new Map<number, number>();
  let w0 = 0;
  return {
    start() {
      c0 = new Map(pids().map((p) => [p, cpuSeconds(p)]));
      w0 = performance.now();
    },
    /** Shares of one core: the server (node) and its children (ffmpeg). */
    stop() {
      const wallS = (performance.now() - w0) / 1000;
      let node = NaN;
      let ffmpeg = 0;
      for (const [p, c] of c0) {
        const d = cpuSeconds(p) - c;
        if (p === pid) node = d;
        else if (Number.isFinite(d)) ffmpeg += d;
      }
      return { node: node / wallS, ffmpeg: ffmpeg / wallS, processes: c0.size };
    },
  };
}
