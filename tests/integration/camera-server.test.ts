/**
 * The camera server against real ffmpeg (Debian's) and real Mosquitto: the test source is
 * announced retained on `arm/arm1/camera/front`; the MJPEG stream gives JPEGs that change and
 * carry a readable time stripe; the WebSocket gives H.264 access units that start with a key
 * frame and that ffmpeg decodes; both kinds' frames are stamped with their capture time, the
 * clock drawn in them, and a re-served MJPEG URL's with the wall clock of their reading (a source
 * whose times are not the wall clock gets arrival times, counted); a killed
 * ffmpeg is restarted and the open streams resume; with
 * a users file, an anonymous viewer is refused and a viewer's log-in is let in; a clean stop
 * removes the announcement, and so does the last will of a server that is killed (whose ffmpeg
 * then dies too): the last two through the `armtwin camera` command. Every server and ffmpeg
 * started here is stopped in afterAll.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { createHash } from 'node:crypto';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import WebSocket from 'ws';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { LoginThrottle, loadUsers } from '@armtwin/auth';
import {
  cameraStreams,
  createMultipartParser,
  decodeH264Message,
  multipartBoundary,
  NAL,
  nalTypes,
  parseCameraMessage,
  readTimeStripe,
  serveCamera,
  type H264Message,
  type MultipartPart,
  type ServedCameras,
} from '@armtwin/camera';
import { REPO_ROOT } from '../helpers/files.ts';
import { useMosquitto } from '../helpers/use-services.ts';

const broker = useMosquitto();
const TOPIC = 'arm/arm1/camera/front';
const USERS_FILE = path.join(REPO_ROOT, 'deploy', 'users.example.json');
const W = 640;
const H = 480;
const servers: ServedCameras[] = [];
const children: ChildProcess[] = [];
const clients: MqttClient[] = [];
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
const basic = (user: string) => `Basic ${Buffer.from(`${user}:${user}-demo`).toString('base64')}`;

afterAll(async () => {
  await Promise.all(servers.map((s) => s.stop()));
  for (const c of children) c.kill('SIGKILL');
  await Promise.all(clients.map((c) => c.endAsync(true)));
});

async function start(
  options: Partial<Parameters<typeof serveCamera>[0]> = {},
): Promise<ServedCameras> {
  const s = await serveCamera({
    cameras: [
      {
        armId: 'arm1',
        camId: 'front',
        label: 'Front',
        source: 'testsrc',
        pose: { position: [600, -400, 450], lookAt: [150, 0, 100] },
        fovDeg: 50,
      },
    ],
    port: 0,
    backoff: { minMs: 200, maxMs: 2000, factor: 2, healthyMs: 5000 },
    ...options,
  });
  servers.push(s);
  return s;
}

/** The retained payloads on `topic`, as they come, from a fresh subscriber. */
async function watchTopic(topic: string): Promise<Buffer[]> {
  const client = await mqtt.connectAsync(broker().url, { reconnectPeriod: 0 });
  clients.push(client);
  const seen: Buffer[] = [];
  client.on('message', (t, payload) => t === topic && seen.push(payload));
  await client.subscribeAsync(topic, { qos: 1 });
  return seen;
}

async function until<T>(
  what: string,
  probe: () => T | undefined | null | false,
  ms = 15_000,
): Promise<T> {
  const end = Date.now() + ms;
  for (;;) {
    const v = probe();
    if (v) return v;
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
    await sleep(50);
  }
}

/** Reads an MJPEG stream: parts as they come, until stop(). */
async function openMjpeg(url: string, authorization?: string) {
  const res = await fetch(url, { headers: authorization ? { authorization } : {} });
  const parts: (MultipartPart & { at: number })[] = [];
  const errors: string[] = [];
  if (res.status !== 200 || !res.body) return { res, parts, errors, stop: async () => {} };
  const parser = createMultipartParser({
    boundary: multipartBoundary(res.headers.get('content-type'))!,
    onPart: (p) => parts.push({ ...p, at: Date.now() }),
    onError: (e) => errors.push(e.kind),
  });
  const reader = res.body.getReader();
  const pump = (async () => {
    for (;;) {
      const r = await reader.read();
      if (r.done) return;
      parser.feed(r.value);
    }
  })().catch(() => {});
  return {
    res,
    parts,
    errors,
    stop: async () => {
      await reader.cancel().catch(() => {});
      await pump;
    },
  };
}

/** Opens an h264-ws stream: messages as they come. */
async function openH264(url: string) {
  const ws = new WebSocket(url);
  const messages: (H264Message & { at: number })[] = [];
  ws.on('message', (d: Buffer) => {
    const m = decodeH264Message(new Uint8Array(d));
    if (m.ok) messages.push({ ...m.message, at: Date.now() });
  });
  const opened = await new Promise<number>((resolve, reject) => {
    ws.once('open', () => resolve(101));
    ws.once('unexpected-response', (_req, res) => resolve(res.statusCode ?? 0));
    ws.once('error', reject);
  });
  return { ws, messages, opened, close: () => ws.terminate() };
}

/** Runs ffmpeg over `input` (stdin) and returns its stdout and stderr. */
function ffmpeg(
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

const gray = (jpeg: Uint8Array) =>
  ffmpeg(['-f', 'mjpeg', '-i', 'pipe:0', '-f', 'rawvideo', '-pix_fmt', 'gray', 'pipe:1'], jpeg);
const alive = (pid: number) => {
  try {
    process.kill(pid, 0);
    return true;
  } catch {
    return false;
  }
};

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
    const payload = await until('the retained announcement', () => seen[0]);
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
    await until('15 JPEG parts', () => s.parts.length >= 15);
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
    await until('40 access units', () => v.messages.length >= 40);
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
    await until('both streams flowing', () => mj.parts.length > 3 && h264.messages.length > 3);
    const pid = cam.server.ffmpegPid('front')!;
    expect(alive(pid)).toBe(true);
    const killedAt = Date.now();
    process.kill(pid, 'SIGKILL');
    const restarted = await until('a new ffmpeg', () => {
      const p = cam.server.ffmpegPid('front');
      return p !== null && p !== pid && p;
    });
    expect(alive(pid)).toBe(false);
    await until(
      'MJPEG parts after the restart',
      () => mj.parts.filter((p) => p.at > killedAt + 300).length >= 5,
    );
    await until(
      'H.264 after the restart',
      () => h264.messages.filter((m) => m.at > killedAt + 300).length >= 5,
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
    await until('pictures in both kinds', () => m.parts.length >= 5 && v.messages.length >= 5);
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
    await until('pictures in both kinds', () => m.parts.length >= 3 && v.messages.length >= 3);
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
    await until('the retained announcement', () => seen.length >= 1);
    const pid = cam.server.ffmpegPid('front')!;
    await cam.stop();
    await until('the empty payload', () => seen.at(-1)?.length === 0);
    expect(alive(pid)).toBe(false);
    const fresh = await watchTopic(TOPIC);
    await sleep(500);
    expect(fresh).toEqual([]); // nothing retained any more
  });
});

describe('camera server with a users file', () => {
  let cam: ServedCameras;
  beforeAll(async () => {
    cam = await start({ access: { logins: new LoginThrottle(loadUsers(USERS_FILE)), token: '' } });
  });

  test('an anonymous viewer gets 401, a viewer’s log-in gets the stream, a device of another arm 403', async () => {
    const url = `${cam.url}/camera/front.mjpeg`;
    const anonymous = await fetch(url);
    expect(anonymous.status).toBe(401);
    expect(anonymous.headers.get('www-authenticate')).toBe('Basic realm="armtwin"');
    expect((await fetch(`${cam.url}/camera/metrics`)).status).toBe(401);
    expect((await fetch(url, { headers: { authorization: basic('arm2') } })).status).toBe(403);

    const viewer = await openMjpeg(url, basic('viewer'));
    expect(viewer.res.status).toBe(200);
    await until('a JPEG for the viewer', () => viewer.parts.length >= 2);
    await viewer.stop();

    const wsUrl = `${cam.url.replace('http', 'ws')}/camera/front.h264`;
    const refused = await openH264(wsUrl);
    expect(refused.opened).toBe(401);
    refused.close();
    const auth = encodeURIComponent(Buffer.from('operator:operator-demo').toString('base64'));
    const operator = await openH264(`${wsUrl}?auth=${auth}`);
    expect(operator.opened).toBe(101);
    await until('an access unit for the operator', () => operator.messages.length >= 1);
    expect(operator.messages[0]!.key).toBe(true);
    operator.close();
    const arm1 = await openH264(
      `${wsUrl}?auth=${encodeURIComponent(Buffer.from('arm1:arm1-demo').toString('base64'))}`,
    );
    expect(arm1.opened).toBe(101); // a device may watch its own arm's camera
    arm1.close();
  });
});

describe('armtwin camera', () => {
  const BIN = path.join(REPO_ROOT, 'apps', 'cli', 'bin', 'armtwin.mjs');
  const topic = 'arm/arm1/camera/cli';

  /** Starts the command; resolves with the process and the URL it prints once serving. */
  async function command(): Promise<{ child: ChildProcess; url: string }> {
    const args = ['camera', '--name', 'cli', '--label', 'CLI', '--source', 'testsrc'];
    args.push('--kinds', 'mjpeg', '--fov', '45', '--port', '0', '--mqtt', broker().url);
    const child = spawn(process.execPath, [BIN, ...args], {
      cwd: REPO_ROOT,
      stdio: ['ignore', 'pipe', 'inherit'],
    });
    children.push(child);
    const url = await new Promise<string>((resolve, reject) => {
      let text = '';
      child.stdout!.on('data', (d: Buffer) => {
        text += d.toString();
        if (text.includes('\n')) resolve(text.split('\n')[0]!);
      });
      child.once('exit', (code) => reject(new Error(`armtwin camera exited with ${code}`)));
    });
    return { child, url };
  }
  /** The ffmpeg the command runs (its only child process). */
  const ffmpegOf = (pid: number) =>
    Number(fs.readFileSync(`/proc/${pid}/task/${pid}/children`, 'utf8').trim().split(' ')[0]);

  test('serves and announces one camera; SIGTERM removes the announcement and ends ffmpeg', async () => {
    const { child, url } = await command();
    expect(url).toMatch(/^http:\/\/127\.0\.0\.1:\d+\/camera\/cli\.mjpeg$/);
    const seen = await watchTopic(topic);
    await until('the retained announcement', () => seen.length >= 1);
    const m = parseCameraMessage(topic, seen[0]!);
    expect(m.type === 'camera' && m.camera).toMatchObject({ url, label: 'CLI', fovDeg: 45 });
    // The latest picture: 503 "no picture yet" until ffmpeg's first frame is in, then a JPEG.
    let jpg = await fetch(url.replace(/\.mjpeg$/, '.jpg'));
    for (const end = Date.now() + 15_000; jpg.status === 503 && Date.now() < end;) {
      await sleep(100);
      jpg = await fetch(url.replace(/\.mjpeg$/, '.jpg'));
    }
    expect(jpg.status).toBe(200);
    expect(jpg.headers.get('content-type')).toBe('image/jpeg');
    const ffmpegPid = ffmpegOf(child.pid!);
    expect(alive(ffmpegPid)).toBe(true);
    child.kill('SIGTERM');
    await until('the empty payload', () => seen.at(-1)?.length === 0);
    await until('ffmpeg gone', () => !alive(ffmpegPid), 5000);
  });

  test('killed outright: its last will removes the announcement, and its ffmpeg does not outlive it', async () => {
    const { child } = await command();
    const seen = await watchTopic(topic);
    await until('the retained announcement', () => seen.at(-1)?.length);
    const ffmpegPid = ffmpegOf(child.pid!);
    child.kill('SIGKILL');
    await until('the last will', () => seen.at(-1)?.length === 0);
    await until('its ffmpeg gone', () => !alive(ffmpegPid), 5000);
  });
});
