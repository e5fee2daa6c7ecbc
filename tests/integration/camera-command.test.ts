/**
 * The `armtwin camera` command against real ffmpeg (Debian's) and real Mosquitto: it serves and
 * announces one camera retained; SIGTERM removes the announcement and ends its ffmpeg, and so
 * does the last will of a command that is killed (whose ffmpeg then dies too). (The camera
 * server itself: camera-server.test.ts.) Every command started here is killed in afterAll.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { parseCameraMessage } from '@armtwin/camera';
import { REPO_ROOT } from '../helpers/files.ts';
import { alive, firstChildPid } from '../helpers/pids.ts';
import { until } from '../helpers/until.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { useTopicWatch } from '../helpers/use-topic-watch.ts';

const broker = useMosquitto();
const watchTopic = useTopicWatch(() => broker().url);
const children: ChildProcess[] = [];
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

afterAll(() => {
  for (const c of children) c.kill('SIGKILL');
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
  const ffmpegOf = firstChildPid;

  test('serves and announces one camera; SIGTERM removes the announcement and ends ffmpeg', async () => {
    const { child, url } = await command();
    expect(url).toMatch(/^http:\/\/127\.0\.0\.1:\d+\/camera\/cli\.mjpeg$/);
    const seen = await watchTopic(topic);
    await until(() => seen.length >= 1, 15_000, 'the retained announcement');
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
    await until(() => seen.at(-1)?.length === 0, 15_000, 'the empty payload');
    await until(() => !alive(ffmpegPid), 5000, 'ffmpeg gone');
  });

  test('killed outright: its last will removes the announcement, and its ffmpeg does not outlive it', async () => {
    const { child } = await command();
    const seen = await watchTopic(topic);
    await until(() => seen.at(-1)?.length, 15_000, 'the retained announcement');
    const ffmpegPid = ffmpegOf(child.pid!);
    child.kill('SIGKILL');
    await until(() => seen.at(-1)?.length === 0, 15_000, 'the last will');
    await until(() => !alive(ffmpegPid), 5000, 'its ffmpeg gone');
  });
});
