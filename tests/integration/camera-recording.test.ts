/**
 * Camera recording (docs/cameras-recording.md) with a real camera server (Debian's ffmpeg, the
 * test source), real Mosquitto and the middleware as a process: the middleware finds the camera
 * by its retained announcement and records its H.264 stream in 2 s MP4 segments. The camera
 * server is restarted, then the middleware: each leaves exactly one gap; every segment decodes
 * with ffmpeg, no `.part` is left, and no frame is recorded twice (the frame times, read from
 * the files' packets and names, only go forward). The HTTP API lists the segments and sends them
 * byte for byte; `/metrics` counts them; a middleware started with a smaller size bound deletes
 * the oldest segment first.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { serveCamera, type ServedCameras } from '@armtwin/camera';
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
    ],
    port,
    mqttUrl: broker().url,
  });
  cameras.push(c);
  await c.announced;
  return c;
}

async function listed(port: number): Promise<Listed[]> {
  const res = await fetch(`http://127.0.0.1:${port}/api/arms/arm1/cameras/front/segments`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { segments: Listed[] }).segments;
}

/** Waits until `count` segments that start after `afterMs` are listed. */
async function segmentsAfter(port: number, afterMs: number, count: number): Promise<Listed[]> {
  const end = Date.now() + 60_000;
  for (;;) {
    const fresh = (await listed(port)).filter((s) => s.startMs > afterMs);
    if (fresh.length >= count) return fresh;
    if (Date.now() > end) throw new Error(`no ${count} segments after ${afterMs}`);
    await sleep(250);
  }
}

/** Epoch ms of every frame of a segment: its name's start + each packet's time. */
function frameTimes(file: string, startMs: number): number[] {
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
    const one = segments[segments.length - 1]!;
    const sent = Buffer.from(
      await (await fetch(`http://127.0.0.1:${mw2.port}${one.url}`)).arrayBuffer(),
    );
    const metrics = await mw2.metrics();
    expect(await mw2.stop()).toBe(0);
    await camera.stop();

    // What is on disk is what was listed (plus what the stop finished), all whole.
    const folder = path.join(dir, 'arm1', 'front');
    const files = fs.readdirSync(folder).sort();
    expect(files.filter((f) => !f.endsWith('.mp4'))).toEqual([]);
    expect(files).toEqual(expect.arrayContaining(segments.map((s) => s.name)));
    expect(sent.equals(fs.readFileSync(path.join(folder, one.name)))).toBe(true);
    expect(metrics['camera_segments']).toBeGreaterThanOrEqual(2);
    expect(
      metrics['camera_recording_events_total{event="segments-written"}'],
    ).toBeGreaterThanOrEqual(2);

    const times: number[] = [];
    for (const f of files) {
      const file = path.join(folder, f);
      // ffmpeg decodes every frame without a word on stderr
      const decoded = execFileSync('ffmpeg', ['-v', 'error', '-i', file, '-f', 'null', '-'], {
        stdio: ['ignore', 'pipe', 'pipe'],
      });
      expect(decoded.toString()).toBe('');
      times.push(...frameTimes(file, Number(f.split('-')[0])));
    }
    const steps = times.slice(1).map((t, i) => t - times[i]!);
    expect(Math.min(...steps)).toBeGreaterThan(0); // nothing recorded twice, nothing backwards
    const gaps = steps
      .map((d, i) => ({ from: times[i]!, to: times[i + 1]!, d }))
      .filter((g) => g.d > 1500);
    expect(gaps).toHaveLength(2);
    expect(gaps[0]!.from).toBeLessThan(cameraDown);
    expect(gaps[0]!.to).toBeGreaterThan(cameraDown);
    expect(gaps[1]!.from).toBeLessThan(middlewareDown);
    expect(gaps[1]!.to).toBeGreaterThan(middlewareDown);

    // Retention: a bound that the oldest segment alone is over deletes just that one.
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
