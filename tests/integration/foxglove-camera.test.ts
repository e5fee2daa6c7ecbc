/**
 * Cameras in Foxglove: `armtwin up --camera testsrc --foxglove PORT --users …` (a real ffmpeg
 * test source on the camera server, log-ins on). Foxglove's npm client (`@foxglove/ws-protocol`)
 * logged in as a viewer finds the camera as `/{arm}/camera/{cam}`, `foxglove.CompressedImage`,
 * and receives JPEG frames that ffmpeg decodes to the source's 640×480, with advancing time
 * stamps. The stream is read with each client's own log-in: a device account of another arm,
 * which the camera server does not let watch this arm, gets the camera's refusal and no frame.
 */
import { spawnSync } from 'node:child_process';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freePorts } from '../helpers/services.ts';
import { NpmFoxglove, type Received } from '../helpers/foxglove.ts';
import { USERS_FILE } from './auth-cases.ts';
import { ARMTWIN, startUpProcess, type Child } from './sim-helpers.ts';

const TOPIC = '/arm1/camera/demo';
const N = 8;
let up: Child;
let url = '';
const clients: NpmFoxglove[] = [];

beforeAll(async () => {
  const [httpPort = 0, mqttPort = 0, foxPort = 0] = await freePorts(3);
  up = await startUpProcess(
    [ARMTWIN, 'up'],
    [
      '--no-middleware',
      '--no-web',
      '--users',
      USERS_FILE,
      '--camera',
      'testsrc',
      '--foxglove',
      String(foxPort),
    ],
    { httpPort, mqttPort },
  );
  url = `ws://127.0.0.1:${foxPort}`;
}, 60_000);

afterAll(async () => {
  for (const c of clients) c.close();
  await up?.stop();
});

const connect = async (user: string) => {
  const c = await NpmFoxglove.connect(url, user);
  clients.push(c);
  return c;
};

const ms = (m: Received) => {
  const t = m.body.timestamp as { sec: number; nsec: number };
  return t.sec * 1000 + t.nsec / 1e6;
};

/** ffmpeg's decoding of one JPEG to 8-bit grey: its byte count is width × height. */
function decodedBytes(jpeg: Buffer): number {
  const r = spawnSync(
    'ffmpeg',
    [
      '-v',
      'error',
      '-f',
      'jpeg_pipe',
      '-i',
      'pipe:0',
      '-f',
      'rawvideo',
      '-pix_fmt',
      'gray',
      'pipe:1',
    ],
    { input: jpeg, maxBuffer: 16 * 1024 * 1024 },
  );
  expect(r.stderr.toString()).toBe('');
  expect(r.status).toBe(0);
  return r.stdout.length;
}

describe('cameras as foxglove.CompressedImage', () => {
  test('a viewer receives decodable JPEG frames with advancing time stamps', async () => {
    const viewer = await connect('viewer');
    const channel = await viewer.until(() => viewer.channels.get(TOPIC), 'the camera channel');
    expect(channel.schemaName).toBe('foxglove.CompressedImage');
    const frames = await viewer.subscribe(TOPIC);
    // a test source at 30 frames/s; under a loaded machine ffmpeg may lag: time, not speed, is not
    // what is tested here, so the wait is long and what did come is told if it runs out
    await viewer
      .until(() => frames.length >= N, `${N} frames`, 30_000)
      .catch((err: Error) => {
        throw new Error(
          `${err.message}: ${frames.length} came, ${JSON.stringify(viewer.statuses)}`,
        );
      });
    for (const f of frames.slice(0, N)) {
      expect(f.body).toMatchObject({ format: 'jpeg', frame_id: 'arm1/camera/demo' });
      expect(Number(f.ns / 1_000_000n)).toBe(Math.floor(ms(f)));
    }
    const jpegs = frames.slice(0, N).map((f) => Buffer.from(f.body.data as string, 'base64'));
    for (const j of jpegs)
      expect([j[0], j[1], j.at(-2), j.at(-1)]).toEqual([0xff, 0xd8, 0xff, 0xd9]);
    expect(decodedBytes(jpegs[0]!)).toBe(640 * 480);
    expect(decodedBytes(jpegs[N - 1]!)).toBe(640 * 480);
    // the test source moves: the pictures differ; the stamps advance (two frames ffmpeg hands over
    // in one read may share a millisecond)
    expect(new Set(jpegs.map((j) => j.toString('base64'))).size).toBeGreaterThan(1);
    const stamps = frames.slice(0, N).map(ms);
    for (let i = 1; i < stamps.length; i++)
      expect(stamps[i]!).toBeGreaterThanOrEqual(stamps[i - 1]!);
    expect(stamps.at(-1)!).toBeGreaterThan(stamps[0]!);
  });

  test('a user the camera server does not let watch this arm gets its refusal, no frame', async () => {
    const other = await connect('arm2'); // the device account of arm2
    const frames = await other.subscribe(TOPIC);
    const status = await other.until(
      () => other.statuses.find((s) => s.message.includes('camera')),
      "the camera's refusal",
    );
    expect(status.message).toMatch(/403/);
    expect(frames).toEqual([]);
  });
});
