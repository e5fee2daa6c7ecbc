/**
 * `armtwin up --camera testsrc`: the demo camera on the up's own HTTP port (real ffmpeg), beside
 * MQTT over WebSockets at /mqtt on the same port. The camera is announced retained on the
 * embedded broker (PROTOCOL.md §7), its MJPEG stream gives changing JPEG pictures, and a clean
 * stop removes the announcement and ffmpeg.
 */
import { spawnSync } from 'node:child_process';
import mqtt from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import {
  createMultipartParser,
  multipartBoundary,
  parseCameraMessage,
} from '@armtwin/camera/client';
import { freePorts } from '../helpers/services.ts';
import { startUpProcess, StatusWatcher, type Child } from './sim-helpers.ts';

let up: Child;
let httpPort = 0;
let mqttPort = 0;

beforeAll(async () => {
  [httpPort = 0, mqttPort = 0] = await freePorts(2);
  up = await startUpProcess(
    ['apps/cli/bin/armtwin.mjs', 'up'],
    ['--no-middleware', '--no-web', '--camera', 'testsrc'],
    { httpPort, mqttPort },
  );
});

afterAll(async () => {
  await up?.stop('SIGKILL');
});

/** The retained camera topics of arm1 and their payloads, as a new subscriber sees them. */
async function retainedCameras(): Promise<Map<string, string>> {
  const c = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`, { reconnectPeriod: 0 });
  const seen = new Map<string, string>();
  c.on('message', (topic, payload) => seen.set(topic, payload.toString()));
  await c.subscribeAsync('arm/arm1/camera/+', { qos: 1 });
  await new Promise((r) => setTimeout(r, 500));
  await c.endAsync();
  return seen;
}

/** The first `n` JPEG parts of an MJPEG stream. */
async function mjpegParts(url: string, n: number): Promise<Uint8Array[]> {
  const res = await fetch(url);
  expect(res.status).toBe(200);
  expect(res.headers.get('content-type')).toMatch(/^multipart\/x-mixed-replace; ?boundary=/);
  const parts: Uint8Array[] = [];
  const parser = createMultipartParser({
    boundary: multipartBoundary(res.headers.get('content-type')) ?? '',
    onPart: (p) => parts.push(p.body),
  });
  const reader = res.body!.getReader();
  while (parts.length < n) {
    const { value, done } = await reader.read();
    if (done) break;
    parser.feed(value);
  }
  await reader.cancel();
  return parts.slice(0, n);
}

describe('armtwin up --camera testsrc', () => {
  test('announces the demo camera, retained, with an MJPEG URL on the HTTP port', async () => {
    const seen = await retainedCameras();
    const msg = parseCameraMessage('arm/arm1/camera/demo', seen.get('arm/arm1/camera/demo') ?? '');
    expect(msg).toMatchObject({
      type: 'camera',
      camera: {
        url: `http://127.0.0.1:${httpPort}/camera/demo.mjpeg`,
        kind: 'mjpeg',
        label: 'Demo camera',
        fovDeg: 50,
      },
    });
  });

  test('serves changing JPEG pictures, while /mqtt still takes WebSockets on the same port', async () => {
    const parts = await mjpegParts(`http://127.0.0.1:${httpPort}/camera/demo.mjpeg`, 5);
    expect(parts).toHaveLength(5);
    for (const p of parts)
      expect([p[0], p[1], p.at(-2), p.at(-1)]).toEqual([0xff, 0xd8, 0xff, 0xd9]);
    expect(new Set(parts.map((p) => Buffer.from(p).toString('base64'))).size).toBe(5);

    const w = await StatusWatcher.connect(`ws://127.0.0.1:${httpPort}/mqtt`, 'arm1');
    await w.until(() => (w.positions(0).length >= 3 ? true : undefined), 10_000, 'state over ws');
    await w.close();
  });

  test('a clean stop removes the announcement and ffmpeg', async () => {
    const ffmpegBefore = spawnSync('pgrep', [
      '-P',
      String(up.proc.pid),
      'ffmpeg',
    ]).stdout.toString();
    expect(ffmpegBefore.trim()).not.toBe('');
    // The broker is the up's own: watch the topic from outside while it stops.
    const c = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`, { reconnectPeriod: 0 });
    const removed = new Promise<void>((resolve) =>
      c.on('message', (topic, payload) => {
        if (topic === 'arm/arm1/camera/demo' && payload.length === 0) resolve();
      }),
    );
    await c.subscribeAsync('arm/arm1/camera/+', { qos: 1 });
    up.proc.kill('SIGINT');
    await removed;
    await c.endAsync(true);
    const deadline = Date.now() + 15_000;
    while (up.proc.exitCode === null && Date.now() < deadline)
      await new Promise((r) => setTimeout(r, 100));
    expect(up.proc.exitCode).toBe(0);
    const left = spawnSync('pgrep', ['-f', `ffmpeg.*testsrc`]).stdout.toString().trim();
    expect(left.split('\n').filter((pid) => pid && pid === ffmpegBefore.trim())).toEqual([]);
  });
});
