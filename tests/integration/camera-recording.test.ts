/**
 * Camera recording (docs/cameras-recording.md) with a real camera server (Debian's ffmpeg, the
 * test source), real Mosquitto and the middleware as a process: the middleware finds the cameras
 * by their retained announcements and records `front`'s H.264 stream in 2 s MP4 segments and
 * `side`, which offers only MJPEG, in 2 s `.mjpeg` segments (its JPEGs as served). The camera
 * server is restarted, then the middleware: each leaves exactly one gap in each camera; every
 * segment decodes with ffmpeg, no `.part` is left, and no frame is recorded twice (the frame
 * times, read from the files' packets and names or the JPEG parts' stamps, only go forward).
 * The HTTP API lists the segments and sends them byte for byte, or the one byte range asked for
 * (206, fetched with undici); `/metrics` counts them; a middleware started with a smaller size
 * bound deletes the oldest segment first.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { serveCamera, type ServedCameras } from '@armtwin/camera';
import { readMjpegSegment } from '../helpers/mjpeg-segment.ts';
import { freePort } from '../helpers/ports.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { useMosquitto } from '../helpers/use-services.ts';

const broker = useMosquitto();
const middlewares = useMiddlewares('camera-recording', () => ({ mqttUrl: broker().url }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
const cameras: ServedCameras[] = [];
afterAll(async () => {
  await Promise.all(cameras.map((c) => c.stop()));
});

interface Listed {
  name: string;
  startMs: number;
  endMs: number;
  bytes: number;
  url: string;
}

async function startCamera(port: number): Promise<ServedCameras> {
  const c = await serveCamera({
    cameras: [
      { armId: 'arm1', camId: 'front', label: 'Front', source: 'testsrc', kinds: ['h264-ws'] },
      { armId: 'arm1', camId: 'side', label: 'Side', source: 'testsrc', kinds: ['mjpeg'] },
    ],
    port,
    mqttUrl: broker().url,
  });
  cameras.push(c);
  await c.announced;
  return c;
}

async function listed(port: number, cam = 'front'): Promise<Listed[]> {
  const res = await fetch(`http://127.0.0.1:${port}/api/arms/arm1/cameras/${cam}/segments`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { segments: Listed[] }).segments;
}

/** Waits until `count` segments of each camera that start after `afterMs` are listed. */
async function segmentsAfter(port: number, afterMs: number, count: number): Promise<void> {
  const end = Date.now() + 60_000;
  for (;;) {
    const fresh = await Promise.all(
      ['front', 'side'].map(async (c) =>
        (await listed(port, c)).filter((s) => s.startMs > afterMs),
      ),
    );
    if (fresh.every((f) => f.length >= count)) return;
    if (Date.now() > end) throw new Error(`no ${count} segments after ${afterMs}`);
    await sleep(250);
  }
}

/** Epoch ms of every frame of a segment: its name's start + each packet's time. */
function frameTimes(file: string, startMs: number): number[] {
  if (file.endsWith('.mjpeg')) return readMjpegSegment(file).times;
  const out = execFileSync('ffprobe', [
    ...['-v', 'error', '-select_streams', 'v', '-show_entries', 'packet=pts_time'],
    ...['-of', 'csv=p=0', file],
  ]).toString();
  return out
    .trim()
    .split('\n')
    .map((t) => startMs + Number(t) * 1000);
}

describe('recording a camera beside the history', () => {
  test('a camera-server restart and a middleware restart leave one gap each; every segment decodes; nothing twice; retention deletes the oldest first', async () => {
    const dir = path.join(middlewares.dir(), 'cameras');
    const env = { CAMERA_DIR: dir, CAMERA_SEGMENT_S: '2' };
    const camPort = await freePort();
    let camera = await startCamera(camPort);
    const mw1 = await middlewares.spawn({ env });
    await segmentsAfter(mw1.port, 0, 2);

    // The camera server restarts: one gap, then the recording goes on by itself.
    await camera.stop();
    const cameraDown = Date.now();
    await sleep(3000);
    camera = await startCamera(camPort);
    await segmentsAfter(mw1.port, cameraDown, 2);

    // The middleware restarts (SIGTERM: its last segment is finished), on the same folder.
    expect(await mw1.stop()).toBe(0);
    const middlewareDown = Date.now();
    await sleep(3000);
    const mw2 = await middlewares.spawn({ env });
    await segmentsAfter(mw2.port, middlewareDown, 2);

    const segments = await listed(mw2.port);
    const sideSegments = await listed(mw2.port, 'side');
    const one = segments[segments.length - 1]!;
    const whole = await fetch(`http://127.0.0.1:${mw2.port}${one.url}`);
    expect(whole.headers.get('accept-ranges')).toBe('bytes');
    const sent = Buffer.from(await whole.arrayBuffer());
    // a <video> seeks with byte ranges: one range is answered 206 with just those bytes
    const ranged = async (range: string) => {
      const res = await fetch(`http://127.0.0.1:${mw2.port}${one.url}`, { headers: { range } });
      const body = Buffer.from(await res.arrayBuffer());
      return { status: res.status, contentRange: res.headers.get('content-range'), body };
    };
    const middle = await ranged('bytes=100-1099');
    const end = await ranged('bytes=-64');
    const past = await ranged(`bytes=${one.bytes}-`);
    const metrics = await mw2.metrics();
    expect(await mw2.stop()).toBe(0);
    await camera.stop();

    // What is on disk is what was listed (plus what the stop finished), all whole.
    const folder = path.join(dir, 'arm1', 'front');
    const files = fs.readdirSync(folder).sort();
    const onDisk = fs.readFileSync(path.join(folder, one.name));
    expect(sent.equals(onDisk)).toBe(true);
    expect(middle).toEqual({
      status: 206,
      contentRange: `bytes 100-1099/${one.bytes}`,
      body: onDisk.subarray(100, 1100),
    });
    expect(end).toEqual({
      status: 206,
      contentRange: `bytes ${one.bytes - 64}-${one.bytes - 1}/${one.bytes}`,
      body: onDisk.subarray(-64),
    });
    expect([past.status, past.contentRange]).toEqual([416, `bytes */${one.bytes}`]);
    expect(metrics['camera_segments']).toBeGreaterThanOrEqual(4);
    expect(
      metrics['camera_recording_events_total{event="segments-written"}'],
    ).toBeGreaterThanOrEqual(4);
    expect(metrics['camera_recording_events_total{event="cameras-recorded-mjpeg"}']).toBe(1);

    for (const [cam, ext, list] of [
      ['front', '.mp4', segments],
      ['side', '.mjpeg', sideSegments],
    ] as const) {
      const names = fs.readdirSync(path.join(dir, 'arm1', cam)).sort();
      expect(names.filter((f) => !f.endsWith(ext))).toEqual([]);
      expect(names).toEqual(expect.arrayContaining(list.map((s) => s.name)));
      const times: number[] = [];
      for (const f of names) {
        const file = path.join(dir, 'arm1', cam, f);
        // ffmpeg decodes every frame without a word on stderr (an MJPEG segment: each of its
        // JPEGs, after its parts read whole up to the closing boundary; rawvideo, as the null
        // muxer warns of two frames in one of its own time slots)
        let input = ['-i', file];
        let stdin: Buffer | undefined;
        if (ext === '.mjpeg') {
          const m = readMjpegSegment(file);
          expect([m.closed, m.errors], f).toEqual([true, []]);
          [input, stdin] = [['-f', 'jpeg_pipe', '-i', '-'], m.jpegs];
        }
        const decoded = spawnSync(
          'ffmpeg',
          ['-v', 'error', ...input, '-f', 'rawvideo', '-y', '/dev/null'],
          {
            input: stdin,
          },
        );
        expect([decoded.status, decoded.stderr.toString()], f).toEqual([0, '']);
        times.push(...frameTimes(file, Number(f.split('-')[0])));
      }
      const steps = times.slice(1).map((t, i) => t - times[i]!);
      expect(Math.min(...steps), cam).toBeGreaterThan(0); // nothing twice, nothing backwards
      const gaps = steps
        .map((d, i) => ({ from: times[i]!, to: times[i + 1]!, d }))
        .filter((g) => g.d > 1500);
      expect(gaps, cam).toHaveLength(2);
      expect(gaps[0]!.from).toBeLessThan(cameraDown);
      expect(gaps[0]!.to).toBeGreaterThan(cameraDown);
      expect(gaps[1]!.from).toBeLessThan(middlewareDown);
      expect(gaps[1]!.to).toBeGreaterThan(middlewareDown);
    }

    // Retention: a bound that the oldest segment alone is over deletes just that one.
    const sideFolder = path.join(dir, 'arm1', 'side');
    fs.rmSync(sideFolder, { recursive: true }); // one camera's files, for a plain count
    const sizes = files.map((f) => fs.statSync(path.join(folder, f)).size);
    const total = sizes.reduce((a, b) => a + b, 0);
    const mw3 = await middlewares.spawn({
      env: { ...env, CAMERA_RETENTION_BYTES: String(total - sizes[0]!) },
    });
    expect((await listed(mw3.port)).map((s) => s.name)).toEqual(files.slice(1));
    expect(fs.existsSync(path.join(folder, files[0]!))).toBe(false);
    const m3 = await mw3.metrics();
    expect(m3['camera_recording_events_total{event="segments-deleted-size"}']).toBe(1);
    await mw3.stop();
  });
});
