/**
 * One take's ffmpeg: FLV in on its stdin (./takes.ts decides the frames, `@armtwin/camera`'s
 * flv-writer wraps them), MP4 segments out, the frames copied as they are (`-c copy`: no decode,
 * no encode). ffmpeg's segment muxer cuts at the first key frame after each `segmentS` and, once
 * a segment's file is closed, prints `name,start,end` (seconds from the take's first frame) on
 * fd 3; the segment is then renamed from its `.part` name to its times
 * (./segment-files.ts), so a file with a final name is always whole. Ending stdin makes ffmpeg
 * close the last segment; an ffmpeg that fails leaves `.part` files, which are deleted.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { PART_EXT, segmentName, type Segment } from './segment-files.ts';

export interface SegmenterOptions {
  /** The ffmpeg program. */
  ffmpeg: string;
  /** The camera's folder. */
  dir: string;
  /** Target segment length, s (cut at the next key frame after it). */
  segmentS: number;
  /** Epoch ms of the take's first frame (FLV time 0). */
  baseMs: number;
  onSegment(segment: Pick<Segment, 'name' | 'startMs' | 'endMs' | 'bytes'>): void;
  /** A problem, by kind: `ffmpeg-failed`, `rename-failed`, `part-deleted`. */
  onProblem(kind: string, message: string): void;
}

/** The ffmpeg command line (without the program) of a take starting at `baseMs`. */
export function segmenterArgs(dir: string, segmentS: number, baseMs: number): string[] {
  return [
    ...['-hide_banner', '-nostdin', '-nostats', '-loglevel', 'error'],
    ...['-f', 'flv', '-i', 'pipe:0', '-map', '0:v', '-c', 'copy'],
    ...['-f', 'segment', '-segment_time', String(segmentS), '-segment_format', 'mp4'],
    ...['-reset_timestamps', '1', '-segment_list', 'pipe:3', '-segment_list_type', 'csv'],
    path.join(dir, `${baseMs}-%06d${PART_EXT}`),
  ];
}

export class Segmenter {
  private readonly child: ChildProcess;
  private readonly closed: Promise<void>;
  private listTail = '';
  private stderrTail = '';
  private written = 0;

  constructor(private readonly o: SegmenterOptions) {
    fs.mkdirSync(o.dir, { recursive: true });
    this.child = spawn(o.ffmpeg, segmenterArgs(o.dir, o.segmentS, o.baseMs), {
      stdio: ['pipe', 'ignore', 'pipe', 'pipe'],
    });
    this.child.stdin!.on('error', () => {}); // the exit below says why
    const list = this.child.stdio[3] as NodeJS.ReadableStream;
    list.setEncoding('utf8');
    list.on('data', (text: string) => this.listed(text));
    this.child.stderr!.setEncoding('utf8');
    this.child.stderr!.on(
      'data',
      (t: string) => (this.stderrTail = (this.stderrTail + t).slice(-2000)),
    );
    this.closed = new Promise((resolve) => {
      this.child.once('error', (err) => {
        this.o.onProblem('ffmpeg-failed', `cannot run ${o.ffmpeg}: ${err.message}`);
        resolve();
      });
      this.child.once('close', (code, signal) => {
        if (code !== 0)
          this.o.onProblem(
            'ffmpeg-failed',
            `segmenter ${signal ? `killed by ${signal}` : `exit ${code}`}: ${this.stderrTail.trim().split('\n').pop() ?? ''}`,
          );
        this.deleteParts();
        resolve();
      });
    });
  }

  /** Bytes handed to ffmpeg and not yet taken by it. */
  get backlogBytes(): number {
    return this.child.stdin?.writableLength ?? 0;
  }

  /** Bytes handed to ffmpeg so far. */
  get bytesIn(): number {
    return this.written;
  }

  write(chunk: Uint8Array): void {
    if (!this.child.stdin?.writable) return;
    this.written += chunk.length;
    this.child.stdin.write(chunk);
  }

  /** Ends the take: ffmpeg closes its last segment; resolves once it has exited. */
  async end(): Promise<void> {
    this.child.stdin?.end();
    const hard = setTimeout(() => this.child.kill('SIGKILL'), 10_000);
    await this.closed;
    clearTimeout(hard);
  }

  private listed(text: string): void {
    const lines = (this.listTail + text).split('\n');
    this.listTail = lines.pop()!;
    for (const line of lines) {
      const [name, start, end] = line.trim().split(',');
      if (!name || start === undefined || end === undefined) continue;
      const from = path.join(this.o.dir, path.basename(name));
      const startMs = Math.round(this.o.baseMs + Number(start) * 1000);
      const endMs = Math.round(this.o.baseMs + Number(end) * 1000);
      try {
        const final = segmentName(startMs, endMs);
        fs.renameSync(from, path.join(this.o.dir, final));
        const { size } = fs.statSync(path.join(this.o.dir, final));
        this.o.onSegment({ name: final, startMs, endMs, bytes: size });
      } catch (err) {
        this.o.onProblem('rename-failed', `${from}: ${(err as Error).message}`);
      }
    }
  }

  /** This take's `.part` files that ffmpeg never finished. */
  private deleteParts(): void {
    const prefix = `${this.o.baseMs}-`;
    for (const f of fs.readdirSync(this.o.dir))
      if (f.startsWith(prefix) && f.endsWith(PART_EXT)) {
        fs.rmSync(path.join(this.o.dir, f), { force: true });
        this.o.onProblem('part-deleted', `${f}: ffmpeg did not finish it`);
      }
  }
}
