/**
 * `armtwin up --camera testsrc --users deploy/users.example.json`: the demo camera on the up's
 * own HTTP port (real ffmpeg), beside MQTT over WebSockets at /mqtt on the same port, with
 * log-ins. The camera is announced retained on the embedded broker (PROTOCOL.md §7), its MJPEG
 * stream gives changing JPEG pictures to a viewer's log-in and refuses anyone without one, the
 * in-process middleware records it all the same (with the token the up minted for it:
 * docs/cameras-recording.md), and a clean stop removes the announcement and ffmpeg.
 */
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
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
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-up-camera-'));
const VIEWER = { username: 'viewer', password: 'viewer-demo' };
const viewerHeader = `Basic ${Buffer.from('viewer:viewer-demo').toString('base64')}`;

beforeAll(async () => {
  [httpPort = 0, mqttPort = 0] = await freePorts(2);
  up = await startUpProcess(
    ['apps/cli/bin/armtwin.mjs', 'up'],
    ['--no-web', '--camera', 'testsrc', '--users', 'deploy/users.example.json'],
    { httpPort, mqttPort },
    {
      CAMERA_DIR: path.join(dir, 'cameras'),
      CAMERA_SEGMENT_S: '1',
      SPOOL_DIR: path.join(dir, 'spool'),
      // nothing to store here: the points wait in the spool
      INFLUX_URL: 'http://127.0.0.1:9',
    },
  );
});

afterAll(async () => {
  await up?.stop('SIGKILL');
  fs.rmSync(dir, { recursive: true, force: true });
});

/** The retained camera topics of arm1 and their payloads, as a new subscriber sees them. */
async function retainedCameras(): Promise<Map<string, string>> {
  const c = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`, {
    reconnectPeriod: 0,
    ...VIEWER,
  });
  const seen = new Map<string, string>();
  c.on('message', (topic, payload) => seen.set(topic, payload.toString()));
  await c.subscribeAsync('arm/arm1/camera/+', { qos: 1 });
  await new Promise((r) => setTimeout(r, 500));
  await c.endAsync();
  return seen;
}

/** The first `n` JPEG parts of an MJPEG stream. */
async function mjpegParts(url: string, n: number): Promise<Uint8Array[]> {
  const res = await fetch(url, { headers: { authorization: viewerHeader } });
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

    const w = await StatusWatcher.connect(`ws://127.0.0.1:${httpPort}/mqtt`, 'arm1', VIEWER);
    await w.until(() => (w.positions(0).length >= 3 ? true : undefined), 10_000, 'state over ws');
    await w.close();
  });

  test('refuses a viewer without a log-in, yet the in-process middleware records it', async () => {
    const refused = await fetch(`http://127.0.0.1:${httpPort}/camera/demo.mjpeg`);
    expect(refused.status).toBe(401);
    await refused.body?.cancel();
    const api = `http://127.0.0.1:${httpPort}/api/arms/arm1/cameras/demo/segments`;
    expect((await fetch(api)).status).toBe(401);
    const deadline = Date.now() + 20_000;
    let segments: { name: string; bytes: number; url: string }[] = [];
    while (segments.length < 2 && Date.now() < deadline) {
      await new Promise((r) => setTimeout(r, 250));
      const res = await fetch(api, { headers: { authorization: viewerHeader } });
      segments = ((await res.json()) as { segments: typeof segments }).segments;
    }
    expect(segments.length).toBeGreaterThanOrEqual(2);
    const one = await fetch(`http://127.0.0.1:${httpPort}${segments[0]!.url}`, {
      headers: { authorization: viewerHeader },
    });
    expect(one.headers.get('content-type')).toBe('video/mp4'); // its H.264 stream, as served
    expect((await one.arrayBuffer()).byteLength).toBe(segments[0]!.bytes);
  });

  test('a clean stop removes the announcement and ffmpeg', async () => {
    const ffmpegBefore = spawnSync('pgrep', [
      '-P',
      String(up.proc.pid),
      'ffmpeg',
    ]).stdout.toString();
    expect(ffmpegBefore.trim()).not.toBe('');
    // The broker is the up's own: watch the topic from outside while it stops.
    const c = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`, {
      reconnectPeriod: 0,
      ...VIEWER,
    });
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
