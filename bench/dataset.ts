/**
 * Section 19: datasets (issue 32). One test-source camera (`armtwin camera --kinds h264-ws`,
 * 640×480, 30 frames/s) recorded two ways in the same run, each for the same window:
 * - the recording: the middleware's own `Recordings` (bench/agents/recorder.ts, alone in its
 *   process) as a viewer of the camera's h264-ws stream → FLV → `ffmpeg -c copy -f segment`;
 *   its CPU is node + its ffmpeg, utime + stime from /proc over the window;
 * - baseline: ffmpeg alone copying the same stream to a file: the recorded segments read back
 *   at their own pace (`-re`, concat demuxer) and written with `-c copy -f segment`.
 * Then the export: the LeRobot export's video step (`writeCameraVideo`: the recorded segments
 * cut to one episode at 30 fps, H.264 re-encoded, its pixel statistics) in frames per second of
 * wall time, beside ffmpeg copying the same segments to one file (`-c copy`, no re-encode).
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { readCameraFolder } from '../apps/middleware/src/cameras/index.ts';
import { concatList, writeCameraVideo } from '../apps/middleware/src/export/lerobot/index.ts';
import { startCameraServer, treeMeter } from './lib/camera-server.ts';
import { sleep, spawnChild, until } from './lib/proc.ts';
import { startAgent } from './lib/stack.ts';
import { round } from './lib/stats.ts';
import { fmt, type BenchContext, type Section, type SectionOutput } from './lib/types.ts';

const FFMPEG = 'ffmpeg';
const FPS = 30;

/** Lines an agent prints, as they come. */
function lines(child: { proc: { stdout: NodeJS.ReadableStream | null } }): string[] {
  const out: string[] = [];
  let buf = '';
  child.proc.stdout?.on('data', (d: Buffer) => {
    buf += d.toString();
    for (let nl = buf.indexOf('\n'); nl >= 0; nl = buf.indexOf('\n')) {
      out.push(buf.slice(0, nl));
      buf = buf.slice(nl + 1);
    }
  });
  return out;
}

export const datasetSection: Section = {
  id: 'dataset',
  title: 'Datasets: camera recording CPU, video export rate',
  precheck: () => {
    try {
      execFileSync(FFMPEG, ['-version'], { stdio: 'ignore' });
      return null;
    } catch {
      return 'no ffmpeg';
    }
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const windowS = ctx.quick ? 10 : 30;
    const work = fs.mkdtempSync(path.join(ctx.logDir, 'dataset-'));
    const camera = await startCameraServer({
      armId: 'bench-rec',
      kind: 'h264-ws',
      camId: 'front',
      label: 'Front',
      width: 640,
      height: 480,
      fps: FPS,
      logFile: path.join(ctx.logDir, 'dataset-camera.log'),
    });
    try {
      // The recording.
      const dir = path.join(work, 'recordings');
      const rec = startAgent(
        'recorder',
        [camera.url, dir, '5'],
        path.join(ctx.logDir, 'dataset-recorder.log'),
      );
      const said = lines(rec);
      if (!(await until(() => said.length > 0, 30_000))) throw new Error('recorder not ready');
      await sleep(3000); // connected, first take started
      const recMeter = treeMeter(rec.pid);
      recMeter.start();
      await sleep(windowS * 1000);
      const recCpu = recMeter.stop();
      await rec.stop(15_000);
      const counters = JSON.parse(said[1] ?? '{}') as { frames?: number; bytes?: number };
      const folder = readCameraFolder(dir, 'bench-rec', 'front');
      const segments = folder.segments.map((s) => ({ ...s, file: path.join(folder.dir, s.name) }));
      if (segments.length === 0) throw new Error('nothing recorded');
      const recordedS = (segments.at(-1)!.endMs - segments[0]!.startMs) / 1000;

      // Baseline: ffmpeg alone copying the same stream (the recorded segments, at their pace).
      const list = concatList(segments, 0, Number.MAX_SAFE_INTEGER)!;
      const listFile = path.join(work, 'all.ffconcat');
      fs.writeFileSync(listFile, list.text);
      fs.mkdirSync(path.join(work, 'copy'));
      const copy = spawnChild(
        FFMPEG,
        [
          ...['-hide_banner', '-nostdin', '-v', 'error', '-re', '-f', 'concat', '-safe', '0'],
          ...['-i', listFile, '-c', 'copy', '-f', 'segment', '-segment_time', '5'],
          path.join(work, 'copy', '%03d.mp4'),
        ],
        { logFile: path.join(ctx.logDir, 'dataset-copy.log') },
      );
      await sleep(2000);
      const copyMeter = treeMeter(copy.pid);
      copyMeter.start();
      await sleep(Math.min(windowS, recordedS - 3) * 1000);
      const copyCpu = copyMeter.stop();
      await copy.stop();

      // The export's video step, and ffmpeg copying the same segments to one file.
      const episode = {
        startMs: segments[0]!.startMs + 500,
        frames: Math.floor((recordedS - 1) * FPS),
      };
      const t0 = performance.now();
      await writeCameraVideo({
        ffmpeg: FFMPEG,
        ffprobe: 'ffprobe',
        camId: 'front',
        segments,
        episodes: [episode],
        fps: FPS,
        root: path.join(work, 'ds'),
        work,
      });
      const exportS = (performance.now() - t0) / 1000;
      const t1 = performance.now();
      execFileSync(FFMPEG, [
        ...['-hide_banner', '-nostdin', '-v', 'error', '-f', 'concat', '-safe', '0'],
        ...['-i', listFile, '-c', 'copy', path.join(work, 'copy-all.mp4')],
      ]);
      const copyAllS = (performance.now() - t1) / 1000;
      const recordedFrames = counters.frames ?? NaN;

      const pct = (v: number) => `${fmt(v * 100, 1)} %`;
      const data = {
        windowS,
        recorder: {
          ...recCpu,
          frames: recordedFrames,
          bytes: counters.bytes,
          segments: segments.length,
        },
        baselineCopy: copyCpu,
        export: {
          frames: episode.frames,
          seconds: round(exportS),
          framesPerS: round(episode.frames / exportS),
        },
        copyAll: { seconds: round(copyAllS), framesPerS: round(episode.frames / copyAllS) },
      };
      return {
        settings: {
          camera: '640×480, 30 fps, h264-ws (libx264 veryfast zerolatency, 1.5 Mbit/s cap)',
          segmentS: 5,
          windowS,
          export: 'libx264 veryfast CRF 23, -g 2, yuv420p, 30 fps; stats from ≤64 frames at 80×60',
        },
        data,
        rows: [
          {
            figure: 'camera recording, CPU per camera (node + ffmpeg segmenter), % of a core',
            value: `${pct(recCpu.node + recCpu.ffmpeg)} (node ${pct(recCpu.node)}, ffmpeg ${pct(recCpu.ffmpeg)})`,
            baseline: `ffmpeg -re -c copy of the same stream: ${pct(copyCpu.node + copyCpu.ffmpeg)}`,
            target: 'reported',
            met: null,
          },
          {
            figure: 'LeRobot export, video of one camera (cut, 30 fps H.264, stats), frames/s',
            value: `${fmt(episode.frames / exportS, 0)} (${episode.frames} frames in ${fmt(exportS, 1)} s)`,
            baseline: `ffmpeg -c copy of the same segments: ${fmt(episode.frames / copyAllS, 0)}`,
            target: '≥ 30 (faster than real time)',
            met: episode.frames / exportS >= FPS,
          },
        ],
      };
    } finally {
      await camera.child.stop();
      fs.rmSync(work, { recursive: true, force: true });
    }
  },
};
