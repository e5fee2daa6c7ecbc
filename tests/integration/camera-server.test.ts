/**
 * The camera server against real ffmpeg (Debian's) and real Mosquitto: the test source is
 * announced retained on `arm/arm1/camera/front`; the MJPEG stream gives JPEGs that change and
 * carry a readable time stripe; the WebSocket gives H.264 access units that start with a key
 * frame and that ffmpeg decodes; both kinds' frames are stamped with their capture time, the
 * clock drawn in them, and a re-served MJPEG URL's with the wall clock of their reading (a source
 * whose times are not the wall clock gets arrival times, counted); a killed
 * ffmpeg is restarted and the open streams resume; a clean stop removes the announcement. (Who
 * may watch, with a users file: camera-access.test.ts; the `armtwin camera` command:
 * camera-command.test.ts.) Every server started here is stopped in afterAll.
 */
import { createHash } from 'node:crypto';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { beforeAll, describe, expect, test } from 'vitest';
import {
  cameraStreams,
  NAL,
  nalTypes,
  parseCameraMessage,
  readTimeStripe,
  type ServedCameras,
} from '@armtwin/camera';
import { openH264, openMjpeg } from '../helpers/camera-viewers.ts';
import { ffmpeg, gray } from '../helpers/ffmpeg.ts';
import { alive } from '../helpers/pids.ts';
import { until } from '../helpers/until.ts';
import { useCameraServers } from '../helpers/use-camera-servers.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { useTopicWatch } from '../helpers/use-topic-watch.ts';

const broker = useMosquitto();
const start = useCameraServers();
const watchTopic = useTopicWatch(() => broker().url);
const TOPIC = 'arm/arm1/camera/front';
const W = 640;
const H = 480;
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

describe('camera server with the test source', () => {
  let cam: ServedCameras;
  let mjpegUrl: string;
  let h264Url: string;

  beforeAll(async () => {
    cam = await start({ mqttUrl: broker().url });
    await cam.announced;
    mjpegUrl = `${cam.url}/camera/front.mjpeg`;
    h264Url = `${cam.url.replace('http', 'ws')}/camera/front.h264`;
  });

  test('the camera is announced retained, with its MJPEG and h264-ws URLs, pose and fov', async () => {
    const seen = await watchTopic(TOPIC);
    const payload = await until(() => seen[0], 15_000, 'the retained announcement');
    const m = parseCameraMessage(TOPIC, payload);
    expect(m.type).toBe('camera');
    if (m.type !== 'camera') return;
    expect(m.camera).toMatchObject({ kind: 'mjpeg', label: 'Front', fovDeg: 50 });
    expect(m.camera.pose).toEqual({ position: [600, -400, 450], lookAt: [150, 0, 100] });
    const streams = cameraStreams(m.camera);
    expect(streams.map((s) => s.kind)).toEqual(['mjpeg', 'h264-ws']);
    expect(streams.map((s) => s.url)).toEqual([mjpegUrl, h264Url]);
  });

  test('MJPEG: JPEG parts with Content-Length and X-Timestamp whose bytes change; the stamp is the clock drawn in the frame', async () => {
    const s = await openMjpeg(mjpegUrl);
    expect(s.res.status).toBe(200);
    expect(s.res.headers.get('content-type')).toMatch(/^multipart\/x-mixed-replace; *boundary=/);
    await until(() => s.parts.length >= 15, 15_000, '15 JPEG parts');
    await s.stop();
    expect(s.errors).toEqual([]);
    const hashes = new Set<string>();
    let last = 0;
    for (const p of s.parts) {
      expect(p.headers['content-type']).toBe('image/jpeg');
      expect(Number(p.headers['content-length'])).toBe(p.body.length);
      expect([p.body[0], p.body[1], p.body.at(-2), p.body.at(-1)]).toEqual([
        0xff, 0xd8, 0xff, 0xd9,
      ]);
      const ts = Number(p.headers['x-timestamp']);
      expect(ts).toBeGreaterThanOrEqual(last);
      last = ts;
      hashes.add(createHash('sha1').update(p.body).digest('hex'));
    }
    expect(hashes.size).toBe(s.parts.length); // every picture differs: the clock moves
    const p = s.parts.at(-1)!;
    const { out, code } = await gray(p.body);
    expect(code).toBe(0);
    expect(out.length).toBe(W * H);
    const burned = readTimeStripe(out, W, H);
    const served = Number(p.headers['x-timestamp']);
    expect(burned).not.toBeNull();
    // the frame's capture time (ffmpeg's own time stamp, the instant it drew the clock), not
    // when the server had it
    expect(served).toBe(burned);
  });

  test('h264-ws: a key frame with SPS and PPS first, then access units ffmpeg decodes, stamped with the clock drawn in them', async () => {
    const v = await openH264(h264Url);
    expect(v.opened).toBe(101);
    await until(() => v.messages.length >= 40, 15_000, '40 access units');
    v.close();
    const [first] = v.messages;
    expect(first!.key).toBe(true);
    expect(nalTypes(first!.data).slice(0, 2)).toEqual([NAL.sps, NAL.pps]);
    expect(nalTypes(first!.data)).toContain(NAL.idr);
    for (const m of v.messages.slice(1)) {
      const types = nalTypes(m.data);
      expect(types).toContain(m.key ? NAL.idr : NAL.slice);
    }
    // frames are only ever dropped up to a key frame: after a gap comes a key frame
    for (let i = 1; i < v.messages.length; i++) {
      const [a, b] = [v.messages[i - 1]!, v.messages[i]!];
      expect(b.seq).toBeGreaterThan(a.seq);
      if (b.seq !== a.seq + 1) expect(b.key).toBe(true);
    }
    const stream = Buffer.concat(v.messages.map((m) => m.data));
    const { out, err, code } = await ffmpeg(
      ['-f', 'h264', '-i', 'pipe:0', '-f', 'rawvideo', '-pix_fmt', 'gray', 'pipe:1'],
      stream,
    );
    expect(err).toBe('');
    expect(code).toBe(0);
    expect(out.length).toBe(v.messages.length * W * H);
    // each picture's header stamp is its capture time: the clock ffmpeg drew in it
    const drawn = v.messages.map((_, k) => readTimeStripe(out.subarray(k * W * H), W, H));
    expect(drawn).toEqual(v.messages.map((m) => m.timestampMs));
  });

  test('killing ffmpeg: the server says why, restarts it, and open streams resume', async () => {
    const mj = await openMjpeg(mjpegUrl);
    const h264 = await openH264(h264Url);
    await until(
      () => mj.parts.length > 3 && h264.messages.length > 3,
      15_000,
      'both streams flowing',
    );
    const pid = cam.server.ffmpegPid('front')!;
    expect(alive(pid)).toBe(true);
    const killedAt = Date.now();
    process.kill(pid, 'SIGKILL');
    const restarted = await until(
      () => {
        const p = cam.server.ffmpegPid('front');
        return p !== null && p !== pid && p;
      },
      15_000,
      'a new ffmpeg',
    );
    expect(alive(pid)).toBe(false);
    await until(
      () => mj.parts.filter((p) => p.at > killedAt + 300).length >= 5,
      15_000,
      'MJPEG parts after the restart',
    );
    await until(
      () => h264.messages.filter((m) => m.at > killedAt + 300).length >= 5,
      15_000,
      'H.264 after the restart',
    );
    // the old stream's last frames arrive within ms of the kill; the new ffmpeg starts 200 ms
    // (the back-off) later: the viewer resumes at the new encoder's key frame
    const resumed = h264.messages.find((m) => m.at > killedAt + 150);
    expect(resumed?.key).toBe(true);
    // and what it got, across the restart, decodes without an error
    const got = Buffer.concat(h264.messages.map((m) => m.data));
    const decoded = await ffmpeg(['-f', 'h264', '-i', 'pipe:0', '-f', 'null', '-'], got);
    expect(decoded.err).toBe('');
    expect(decoded.code).toBe(0);
    const metrics = (await (await fetch(`${cam.url}/camera/metrics`)).json()) as {
      cameras: {
        ffmpeg: { restarts: number; pid: number; lastExit: { reason: string } };
        errors: Record<string, number>;
      }[];
    };
    const c = metrics.cameras[0]!;
    expect(c.ffmpeg.restarts, JSON.stringify(c)).toBe(1);
    expect(c.ffmpeg.pid).toBe(restarted);
    expect(c.ffmpeg.lastExit.reason).toContain('SIGKILL');
    expect(c.errors['ffmpeg:exit']).toBe(1);
    await mj.stop();
    h264.close();
  });

  test('an MJPEG URL (this camera) re-served through ffmpeg comes out in both kinds', async () => {
    const again = await start({
      cameras: [
        { armId: 'arm1', camId: 'again', label: 'Again', source: mjpegUrl, passThrough: false },
      ],
    });
    const [a] = again.server.announcements(again.url);
    const [mj, h264] = cameraStreams(a!.announcement);
    const m = await openMjpeg(mj!.url);
    const v = await openH264(h264!.url);
    await until(
      () => m.parts.length >= 5 && v.messages.length >= 5,
      15_000,
      'pictures in both kinds',
    );
    expect(v.messages[0]!.key).toBe(true);
    // every frame's time was the wall clock (no `…:frame-times-arrival`), nothing else went wrong
    // while both viewers watched (read before they leave: a viewer's going is not this test's)
    const metrics = (await (await fetch(`${again.url}/camera/metrics`)).json()) as {
      cameras: { errors: Record<string, number> }[];
    };
    expect(metrics.cameras[0]!.errors).toEqual({});
    await m.stop();
    v.close();
    // stamped when the re-serving ffmpeg read each picture (wall clock, kept by -copyts): after
    // the first server drew its clock in it, before this viewer had it
    const p = m.parts.at(-1)!;
    const stamp = Number(p.headers['x-timestamp']);
    const drawn = readTimeStripe((await gray(p.body)).out, W, H)!;
    expect(stamp).toBeGreaterThanOrEqual(drawn);
    expect(stamp).toBeLessThanOrEqual(p.at);
    for (const h of v.messages) expect(h.timestampMs).toBeLessThanOrEqual(h.at);
    await again.stop();
  });

  test('frame times that are not the wall clock: each frame is stamped when it comes, and counted', async () => {
    // ffmpeg as with a source whose times start at 0: the test source's frames numbered 33 ms
    // apart instead of stamped with the clock
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-camera-'));
    const wrapper = path.join(dir, 'ffmpeg');
    fs.writeFileSync(
      wrapper,
      '#!/usr/bin/env bash\nexec ffmpeg "${@//setpts=RTCTIME\\/1000/setpts=N*33}"\n',
      { mode: 0o755 },
    );
    const before = Date.now();
    const plain = await start({
      ffmpeg: wrapper,
      cameras: [{ armId: 'arm1', camId: 'plain', label: 'Plain', source: 'testsrc' }],
    });
    const m = await openMjpeg(`${plain.url}/camera/plain.mjpeg`);
    const v = await openH264(`${plain.url.replace('http', 'ws')}/camera/plain.h264`);
    await until(
      () => m.parts.length >= 3 && v.messages.length >= 3,
      15_000,
      'pictures in both kinds',
    );
    await m.stop();
    v.close();
    const metrics = (await (await fetch(`${plain.url}/camera/metrics`)).json()) as {
      cameras: { errors: Record<string, number> }[];
    };
    await plain.stop();
    fs.rmSync(dir, { recursive: true, force: true });
    const drawn = readTimeStripe((await gray(m.parts[0]!.body)).out, W, H);
    expect(drawn).toBeLessThan(60_000); // ffmpeg's times: not the clock
    const stamps = [
      ...m.parts.map((p) => [Number(p.headers['x-timestamp']), p.at]),
      ...v.messages.map((h) => [h.timestampMs, h.at]),
    ];
    for (const [stamp, at] of stamps) {
      expect(stamp).toBeGreaterThanOrEqual(before);
      expect(stamp).toBeLessThanOrEqual(at!);
    }
    const { errors } = metrics.cameras[0]!;
    expect(errors['jpeg:frame-times-arrival']).toBeGreaterThanOrEqual(3);
    expect(errors['h264:frame-times-arrival']).toBeGreaterThanOrEqual(3);
  });

  test('a clean stop removes the announcement and ends ffmpeg', async () => {
    const seen = await watchTopic(TOPIC);
    await until(() => seen.length >= 1, 15_000, 'the retained announcement');
    const pid = cam.server.ffmpegPid('front')!;
    await cam.stop();
    await until(() => seen.at(-1)?.length === 0, 15_000, 'the empty payload');
    expect(alive(pid)).toBe(false);
    const fresh = await watchTopic(TOPIC);
    await sleep(500);
    expect(fresh).toEqual([]); // nothing retained any more
  });
});
