/// <reference lib="dom" />
/**
 * A LeRobot dataset into the HUD, end to end: the dataset is written by LeRobot 0.6.1's own
 * writer (`LeRobotDataset.create`, `add_frame`, `save_episode`; tests/helpers/lerobot/
 * make_dataset.py in the pyenv-lerobot venv), picked as a folder in the History panel's replay
 * (Chromium, real Mosquitto, a simulated SO-101), and played on the amber sibling. Its joints on
 * the twin match the file, frame by frame, in armtwin's units (the gripper back from 0–100 %);
 * its camera (`observation.images.front`, LeRobot's own AV1 encoding, both episodes in one v3.0
 * MP4) shows that frame's picture under the scrubber, paused and at 4×; "Make plan from this
 * range" turns it into a plan.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { degreesFromLerobot } from '@armtwin/robot';
import { expect, shot, test } from './fixtures.ts';
import { loadProfile, startProfiledArm } from './support/profiled-arm.ts';
import { runLerobotScript } from '../helpers/lerobot-python.ts';

const SO101 = loadProfile('so101');
const FPS = 30;
/** make_dataset.py draws frame k of episode e as the number 64 e + k in eight bars. */
const CAMERA = { key: 'front', width: 160, height: 120 };

/** Episode e's frame k in LeRobot's units: every joint sweeps, the gripper opens 0 → 87 %. */
function frame(e: number, k: number): number[] {
  const s = Math.sin((k / FPS) * Math.PI) * (e + 1);
  return [20 * s, -10 + 15 * s, 30 - 12 * s, 8 * s, 45 * s, (k * 87) / 59];
}
const EPISODES = [
  { task: 'sweep the shoulder', n: 60 },
  { task: 'wave twice as far', n: 45 },
].map((ep, e) => {
  const state = Array.from({ length: ep.n }, (_, k) => frame(e, k));
  return { task: ep.task, state, action: state.map((row) => row.map((v) => v + 0.5)) };
});

let root = '';

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}) => {
  test.setTimeout(180_000);
  root = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-import-')), 'so101-sweep');
  runLerobotScript(
    'make_dataset.py',
    { root, fps: FPS, camera: CAMERA, episodes: EPISODES },
    'lerobot, numpy',
  );
});

/**
 * A copy of the dataset whose camera is MPEG-4 Part 2 (ffmpeg's `mpeg4`), a codec no Chromium
 * decodes, and said so in info.json; the frames and meta/episodes are the original's.
 */
function undecodableCopy(): string {
  const copy = path.join(path.dirname(root), 'so101-mpeg4');
  fs.cpSync(root, copy, { recursive: true });
  const key = `observation.images.${CAMERA.key}`;
  const infoPath = path.join(copy, 'meta/info.json');
  const info = JSON.parse(fs.readFileSync(infoPath, 'utf8')) as {
    features: Record<string, { info: Record<string, unknown> }>;
  };
  info.features[key]!.info['video.codec'] = 'mpeg4';
  fs.writeFileSync(infoPath, JSON.stringify(info));
  const size = `${CAMERA.width}x${CAMERA.height}`;
  execFileSync('ffmpeg', [
    ...['-y', '-loglevel', 'error', '-f', 'lavfi', '-i', `testsrc=size=${size}:rate=${FPS}`],
    ...['-t', '4', '-c:v', 'mpeg4', path.join(copy, `videos/${key}/chunk-000/file-000.mp4`)],
  ]);
  return copy;
}

test.afterAll(() => {
  if (root) fs.rmSync(path.dirname(root), { recursive: true, force: true });
});

interface ImportHook {
  __armtwin?: {
    ready: boolean;
    replay: {
      angles: Float64Array;
      actionAngles: Float64Array;
      version: number;
      record: { times: number[]; start: number; stop: number } | null;
      seek(t: number): void;
    };
    viewer: { drawnWorld: { getObjectByName(n: string): unknown } };
  };
}

/** Seeks the replay to frame k; its servo angles there. */
async function atFrame(page: Page, k: number) {
  // The version before the seek: the frame loop bumps it once it has drawn the new position.
  const seen = await page.evaluate((i) => {
    const replay = (window as unknown as ImportHook).__armtwin!.replay;
    const v = replay.version;
    replay.seek(replay.record!.times[i]!);
    return v;
  }, k);
  await page.waitForFunction(
    (v) => (window as unknown as ImportHook).__armtwin!.replay.version > v,
    seen,
  );
  return page.evaluate(() => {
    const replay = (window as unknown as ImportHook).__armtwin!.replay;
    return { angles: Array.from(replay.angles), actions: Array.from(replay.actionAngles) };
  });
}

/** The dataset camera's picture as the user sees it: the number its eight bars draw. */
function shownNumber(page: Page) {
  return page
    .getByTestId('replay-video-dataset-front')
    .locator('video')
    .evaluate((v) => {
      const video = v as HTMLVideoElement;
      if (video.hidden || video.seeking || video.readyState < HTMLMediaElement.HAVE_CURRENT_DATA)
        return null;
      const c = document.createElement('canvas');
      [c.width, c.height] = [video.videoWidth, video.videoHeight];
      const g = c.getContext('2d')!;
      g.drawImage(video, 0, 0);
      let n = 0;
      for (let bit = 0; bit < 8; bit++) {
        const [r] = g.getImageData(((bit + 0.5) * c.width) / 8, c.height / 2, 1, 1).data;
        n = n * 2 + (r! > 128 ? 1 : 0);
      }
      return n;
    });
}

/** The three.js replay sibling's joints (deg), or null while it is not shown. */
function drawnJoints(page: Page) {
  return page.evaluate(
    (joints) => {
      const hook = (window as unknown as ImportHook).__armtwin!;
      const robot = hook.viewer.drawnWorld.getObjectByName('replay sibling') as
        { visible: boolean; joints: Record<string, { angle: number }> } | undefined;
      return robot?.visible ? joints.map((j) => (robot.joints[j]!.angle * 180) / Math.PI) : null;
    },
    SO101.servos.map((s) => s.joint),
  );
}

test('a dataset written by LeRobot plays on the twin with the file’s joint values', async ({
  page,
  stack,
}, testInfo) => {
  test.setTimeout(120_000);
  const arm = await startProfiledArm(
    stack.broker.url,
    `e2e-import-${process.pid}`,
    SO101,
    testInfo.outputPath('sim-so101.log'),
  );
  try {
    await page.goto(
      `${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=${arm.id}&role=operator&render=main`,
    );
    await page.waitForFunction(() => (window as unknown as ImportHook).__armtwin?.ready === true);
    await page.locator('summary', { hasText: 'History' }).click();
    await page.getByRole('tab', { name: 'Replay' }).click();
    await page.getByLabel('LeRobot dataset folder').setInputFiles(root);
    const note = page.getByTestId('import-note');
    await expect(note).toHaveText(
      'so101-sweep: LeRobot v3.0, 2 episode(s) at 30 fps, so101_follower.',
    );
    await expect(page.getByLabel('Dataset episode')).toContainText(
      '1: wave twice as far (45 frames)',
    );
    await page.getByLabel('Dataset episode').selectOption('1');
    await page.getByRole('button', { name: 'Play episode' }).click();
    await expect(note).toContainText(
      'Episode 1 ("wave twice as far") loaded on the replay: 45 frames',
    );
    // The arm's own (recorded) cameras are its history's, not the episode's: no line about them.
    await expect(page.getByText(/: joints only\./)).toHaveCount(0);

    // Frame by frame: the file's values (float32), in armtwin's servo degrees, on the sibling.
    const file = EPISODES[1]!.state;
    for (const k of [0, 7, 22, 44]) {
      const want = SO101.servos.map((s, i) => degreesFromLerobot(s, Math.fround(file[k]![i]!)));
      const seen = await atFrame(page, k);
      seen.angles.forEach((a, i) => expect(a, `servo ${i}, frame ${k}`).toBeCloseTo(want[i]!, 3));
      // Its action (the commanded targets) beside it, from the file's own column.
      const action = EPISODES[1]!.action[k]!;
      seen.actions.forEach((a, i) =>
        expect(a, `action ${i}, frame ${k}`).toBeCloseTo(
          degreesFromLerobot(SO101.servos[i]!, Math.fround(action[i]!)),
          3,
        ),
      );
      // The drawn model's joints (URDF degrees: the servo angle at polarity 1, offset 0), once
      // the frame after the seek is drawn (the version is bumped before the model is posed).
      await expect
        .poll(
          async () => (await drawnJoints(page))?.map((a, i) => Math.abs(a - want[i]!) < 0.005),
          { message: `the drawn model at frame ${k}` },
        )
        .toEqual(want.map(() => true));
      // Its camera at that instant: episode 1's frame k, from the middle of the shared MP4.
      await expect
        .poll(() => shownNumber(page), { message: `the dataset video at frame ${k}` })
        .toBe(64 + k);
    }
    // Written beside each joint's state.
    await expect(page.getByTestId('replay-angles')).toHaveText(
      new RegExp(
        SO101.servos.map((s) => `${s.name} -?[\\d.]+° \\(action -?[\\d.]+°\\)`).join(' · '),
      ),
    );
    const video = page.getByTestId('replay-video-dataset-front').locator('video');
    expect(await video.evaluate((v) => (v as HTMLVideoElement).paused)).toBe(true);
    expect(await atFrame(page, 44).then((s) => s.angles[5])).toBeCloseTo(
      degreesFromLerobot(SO101.servos[5]!, Math.fround((44 * 87) / 59)),
      3,
    );
    await shot(page, testInfo, 'dataset-import');

    // Played at 4× from frame 7: the video plays at 4× and stops with the joints on the last frame.
    await atFrame(page, 7);
    await page.getByLabel('Replay speed').selectOption('4');
    await page.getByRole('button', { name: 'Play', exact: true }).click();
    await expect.poll(() => video.evaluate((v) => (v as HTMLVideoElement).playbackRate)).toBe(4);
    await expect.poll(() => shownNumber(page), { message: 'the last frame' }).toBe(64 + 44);
    await expect.poll(() => video.evaluate((v) => (v as HTMLVideoElement).paused)).toBe(true);

    // Played as a recording: a plan from it, to rehearse in Model mode and run.
    await page.getByRole('button', { name: 'Make plan from this range' }).click();
    await expect(page.getByTestId('teach-note')).toContainText('Plan made:');

    // A camera in a codec the browser cannot decode: said in place of the picture, not blank.
    await page.getByLabel('LeRobot dataset folder').setInputFiles(undecodableCopy());
    await expect(note).toHaveText(
      'so101-mpeg4: LeRobot v3.0, 2 episode(s) at 30 fps, so101_follower.',
    );
    await page.getByRole('button', { name: 'Play episode' }).click();
    const camera = page.getByTestId('replay-video-dataset-front');
    await expect(camera.getByRole('alert')).toContainText(
      'front (dataset): this browser cannot decode its mpeg4 video, so no picture is shown',
    );
    await expect(camera.locator('video')).toBeHidden();
    await shot(page, testInfo, 'dataset-import-undecodable');
  } finally {
    await arm.stop();
  }
});
