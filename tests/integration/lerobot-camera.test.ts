/**
 * armtwin's cameras in LeRobot's observations: the real camera server (`armtwin camera`, real
 * ffmpeg's test source with its burned-in clock, MJPEG) announcing `front` on a simulated SO-101
 * follower's arm, on a real Mosquitto, and LeRobot 0.6.1's own code building the robot plugin of
 * packages/lerobot/python from its command-line config (`--armtwin_cameras='{front: {…}}'`).
 * Shown: LeRobot's dataset features hold `observation.images.front` at the configured size; each
 * `get_observation` holds the camera's picture, RGB of that shape, and it is fresh: the clock
 * ffmpeg burned into it is close to now and advances from one observation to the next.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { readTimeStripe } from '@armtwin/camera/client';
import { startPluginScript } from '../helpers/lerobot-python.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { startSo101Follower } from './so101-follower.ts';
import { armtwin, type Child } from './sim-helpers.ts';

const broker = useMosquitto();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-lerobot-camera-'));
const ARM = 'follower';
const W = 640;
const H = 480;

let follower: Child;
let camera: Child;

beforeAll(() => {
  follower = startSo101Follower(broker().url, ARM, path.join(dir, 'models'));
  camera = armtwin([
    ...['camera', '--name', 'front', '--arm', ARM, '--source', 'testsrc', '--kinds', 'mjpeg'],
    ...['--size', `${W}x${H}`, '--port', '0', '--mqtt', broker().url],
  ]);
});

afterAll(async () => {
  await camera?.stop();
  await follower?.stop('SIGKILL');
  fs.rmSync(dir, { recursive: true, force: true });
});

interface Observed {
  features: Record<string, number[]>;
  images: { shape: number[]; dtype: string; red: string }[];
  positions: number[];
}

/** tests/helpers/lerobot/camera_armtwin.py with `input`; its JSON. */
async function observe(input: object): Promise<Observed> {
  const py = startPluginScript('camera_armtwin.py', input);
  const code = await py.exited;
  if (code !== 0)
    throw new Error(
      `camera_armtwin.py exited ${code}:\n${py.err().slice(-3000)}\ncamera server:\n${camera.output().slice(-2000)}`,
    );
  return JSON.parse(py.out()) as Observed;
}

test("get_observation holds armtwin's camera picture, of the configured shape and fresh", async () => {
  const asked = Date.now();
  const o = await observe({
    broker: broker().url,
    arm: ARM,
    user: 'lerobot',
    camera: 'front',
    width: W,
    height: H,
    n: 3,
    interval_s: 0.5,
  });
  // LeRobot's own dataset features of the plugin's observation: the joints and the camera.
  expect(o.features['observation.images.front']).toEqual([H, W, 3]);
  expect(o.features['observation.state']).toEqual([6]);
  expect(o.images).toHaveLength(3);
  const clocks = o.images.map((img) => {
    expect(img.shape).toEqual([H, W, 3]);
    expect(img.dtype).toBe('uint8');
    const red = new Uint8Array(Buffer.from(img.red, 'base64'));
    expect(red.length).toBe(W * H);
    return readTimeStripe(red, W, H);
  });
  // ffmpeg's clock in each picture: readable, made after LeRobot was asked (not an old picture
  // kept), and moving on between observations half a second apart.
  expect(clocks.every((c) => c !== null)).toBe(true);
  const [first, second, last] = clocks as number[];
  expect(first).toBeGreaterThan(asked);
  expect(second).toBeGreaterThan(first!);
  expect(last).toBeGreaterThan(second!);
  expect(o.positions.every(Number.isFinite)).toBe(true);
}, 120_000);
