/**
 * The durable spool: every point is on disk before its MQTT message is acknowledged, and
 * stays there until InfluxDB has it.
 *
 *   <dir>/journal.lp                 the open segment: sealed batches and the open one; one
 *                                    write(2) per commit, i.e. per event-loop turn of MQTT
 *                                    messages (../README.md § Spool)
 *   <dir>/batches/<seq>-<n>.lp       full segments of n points, oldest = smallest seq
 *   <dir>/rejected/<seq>-<n>.lp(.err) batches InfluxDB refused as bad data, with the reason
 *
 * A batch is sealed at BATCH_SIZE points or FLUSH_INTERVAL_MS: it becomes a range of the open
 * segment, fdatasync'd off the main thread (./spool-segment.ts). A segment holds up to
 * `segmentBatches` batches or `segmentBytes`; then it is renamed into batches/ and the next
 * commit starts another. The shipper writes sealed batches oldest-first; a full segment is
 * unlinked once InfluxDB accepted every batch in it, the open one when it holds nothing unshipped
 * (at a stop, or when every batch left and no point is open). On start, a journal left by a crash
 * is sealed first (a torn last line, never acknowledged, is cut), so a restarted middleware
 * replays everything: after a crash a segment is replayed whole, batches InfluxDB already had
 * included (the same points at the same times, which InfluxDB keeps once). The appends are not
 * fsync'd one by one: a SIGKILL loses nothing (the page cache survives), a power cut can lose
 * the open batch and a batch sealed in the last milliseconds whose fsync had not finished.
 *
 * The next journal is created ahead, off the main thread (./journal-spares.ts): the first commit
 * after a segment is full renames a ready empty file to `journal.lp`, and creates one only if none
 * is ready.
 *
 * `hold` takes a message's lines into memory, `commit` appends everything held in one write;
 * the MQTT edge acknowledges the messages of a commit only after it (src/mqtt.ts). `append` is
 * both at once.
 */
import fs from 'node:fs';
import path from 'node:path';
import { JournalSpares } from './journal-spares.ts';
import { Segment, type SegmentHooks } from './spool-segment.ts';

export interface SpoolEntry {
  seq: number;
  points: number;
  bytes: number;
  /** The file it is a range of; null if the disk failed and the batch lives only in memory. */
  segment: Segment | null;
  /** Where in that file it starts. */
  offset: number;
  /** The body, when cached in memory. */
  body?: string;
}

export interface SpoolOptions {
  dir: string;
  /** Bound on sealed + open bytes; `full` beyond it. */
  maxBytes: number;
  /** Bodies of at most this many bytes in total are cached in memory (the rest re-read). */
  cacheBytes?: number;
  /** Batches per spool file (default 32); 1 gives every batch a file of its own. */
  segmentBatches?: number;
  /** Bytes per spool file: a segment this big takes no further batch (default 8 MiB). */
  segmentBytes?: number;
  /** Called on disk errors (counted and logged by the caller); the data stays in memory. */
  onDiskError?: (op: string, err: Error) => void;
}

const NAME = /^(\d{12})-(\d+)\.lp$/;
const pad = (n: number) => String(n).padStart(12, '0');

export class Spool {
  private readonly batchesDir: string;
  private readonly rejectedDir: string;
  private readonly journal: string;
  private readonly spares: JournalSpares;
  private readonly hooks: SegmentHooks;
  /** The open segment (the journal); null until the first commit after a full one. */
  private seg: Segment | null = null;
  private nextSeq = 1;
  /** The open batch's text (for the cache), and its tail not yet written to the journal. */
  private open = '';
  private held = '';
  private openPoints = 0;
  private openBytes = 0;
  /** Where the open batch starts in the journal; whether one of its appends failed. */
  private openStart = 0;
  private openFailed = false;
  private cached = 0;
  /** Disk work off the main thread not finished yet (fsyncs, removals), and who waits for it. */
  private pending = 0;
  private readonly waiting: (() => void)[] = [];
  private readonly cacheBytes: number;
  readonly queue: SpoolEntry[] = [];
  /** Bytes and points of the sealed batches. */
  sealedBytes = 0;
  sealedPoints = 0;

  constructor(private readonly opts: SpoolOptions) {
    this.batchesDir = path.join(opts.dir, 'batches');
    this.rejectedDir = path.join(opts.dir, 'rejected');
    this.journal = path.join(opts.dir, 'journal.lp');
    this.hooks = {
      started: () => this.pending++,
      finished: () => this.done(),
      onError: (op, err) => this.opts.onDiskError?.(op, err),
    };
    this.spares = new JournalSpares(opts.dir, {
      ...this.hooks,
      onError: (err) => this.opts.onDiskError?.('prepare', err),
    });
    this.cacheBytes = opts.cacheBytes ?? 16 * 1024 * 1024;
  }

  /** Creates the folders, seals a journal left by a crash, lists what waits. Returns that. */
  init(): { files: number; points: number } {
    fs.mkdirSync(this.batchesDir, { recursive: true });
    fs.mkdirSync(this.rejectedDir, { recursive: true });
    const names = [...fs.readdirSync(this.batchesDir), ...fs.readdirSync(this.rejectedDir)];
    for (const name of names) {
      const m = NAME.exec(name);
      if (m) this.nextSeq = Math.max(this.nextSeq, Number(m[1]) + 1);
    }
    for (const name of fs.readdirSync(this.batchesDir).sort()) {
      const m = NAME.exec(name);
      if (!m) continue;
      const file = path.join(this.batchesDir, name);
      this.pushFile(file, Number(m[1]), Number(m[2]), fs.statSync(file).size);
    }
    if (fs.existsSync(this.journal)) {
      let text = fs.readFileSync(this.journal, 'latin1');
      const end = text.lastIndexOf('\n');
      text = end < 0 ? '' : text.slice(0, end + 1); // a torn last line was never acknowledged
      const points = text ? text.split('\n').length - 1 : 0;
      if (points > 0) this.writeSealed(text, points);
      fs.rmSync(this.journal);
    }
    this.spares.init();
    return { files: this.queue.length, points: this.sealedPoints };
  }

  get bytes(): number {
    return this.sealedBytes + this.openBytes;
  }
  get full(): boolean {
    return this.bytes >= this.opts.maxBytes;
  }
  get pendingPoints(): number {
    return this.openPoints;
  }

  /** Appends one message's lines to the open batch (on disk before this returns). */
  append(lines: readonly string[]): void {
    this.hold(lines);
    this.commit();
  }

  /** Adds one message's lines to the open batch, in memory until the next `commit`. */
  hold(lines: readonly string[]): void {
    let body = '';
    for (const line of lines) body += line + '\n';
    this.held += body;
    this.openPoints += lines.length;
    this.openBytes += body.length;
  }

  /**
   * Writes what `hold` took since the last commit to the journal, in one write at the journal's
   * end as this spool counts it (a positioned write: after a failed or short one, the next
   * overwrites what it left).
   */
  commit(): void {
    if (this.held === '') return;
    const body = this.held;
    this.held = '';
    this.open += body;
    try {
      const seg = (this.seg ??= this.startSegment());
      const n = fs.writeSync(seg.fd!, body, seg.size, 'latin1');
      if (n !== body.length) throw new Error(`short write: ${n} of ${body.length} bytes`);
      seg.size += n;
    } catch (err) {
      this.openFailed = true;
      this.opts.onDiskError?.('append', err as Error);
    }
  }

  /**
   * Seals the open batch into the queue; null if it was empty. The batch stays where it is, a
   * range of the journal, fsync'd off the main thread (libuv's pool), so a seal never blocks
   * intake on the disk; the batch can be shipped meanwhile (its bytes are in the page cache).
   * A full segment is renamed into batches/ (its last sync and close off the main thread).
   */
  seal(): SpoolEntry | null {
    if (this.openPoints === 0) return null;
    this.commit();
    const body = this.open;
    const points = this.openPoints;
    this.open = '';
    this.openPoints = 0;
    this.openBytes = 0;
    const seq = this.nextSeq++;
    const entry: SpoolEntry = { seq, points, bytes: body.length, segment: null, offset: 0, body };
    const seg = this.seg;
    if (seg && !this.openFailed) {
      entry.segment = seg;
      entry.offset = this.openStart;
      seg.live++;
      seg.batches++;
      seg.points += points;
      seg.lastSeq = seq;
      if (
        seg.batches >= (this.opts.segmentBatches ?? 32) ||
        seg.size >= (this.opts.segmentBytes ?? 8 << 20)
      )
        this.rotate(seg);
      else seg.sync();
    } else if (seg) seg.size = this.openStart; // the batch lives in memory; its range is reused
    this.openFailed = false;
    this.openStart = this.seg?.size ?? 0;
    this.push(entry);
    return entry;
  }

  /**
   * Resolves once the disk work done off the main thread has finished: every sealed batch is on
   * the disk itself (fsync'd), every removed batch's file is gone.
   */
  settled(): Promise<void> {
    if (this.pending === 0) return Promise.resolve();
    return new Promise((resolve) => this.waiting.push(resolve));
  }

  private done(): void {
    if (--this.pending === 0) for (const f of this.waiting.splice(0)) f();
  }

  /** Adds a whole batch as a file of its own (sync mode's failed writes, a crashed journal). */
  writeSealed(body: string, points: number): SpoolEntry {
    const seq = this.nextSeq++;
    const file = path.join(this.batchesDir, `${pad(seq)}-${points}.lp`);
    try {
      const tmp = `${file}.tmp`;
      const fd = fs.openSync(tmp, 'w');
      fs.writeSync(fd, body, null, 'latin1');
      fs.fsyncSync(fd);
      fs.closeSync(fd);
      fs.renameSync(tmp, file);
      return this.pushFile(file, seq, points, body.length, body);
    } catch (err) {
      this.opts.onDiskError?.('write', err as Error);
    }
    const entry: SpoolEntry = { seq, points, bytes: body.length, segment: null, offset: 0, body };
    this.push(entry);
    return entry;
  }

  /** The oldest sealed batch. */
  peek(): SpoolEntry | undefined {
    return this.queue[0];
  }

  read(entry: SpoolEntry): string {
    if (entry.body !== undefined) return entry.body;
    const fd = fs.openSync(entry.segment!.file, 'r');
    try {
      const buf = Buffer.allocUnsafe(entry.bytes);
      let got = 0;
      for (let n = 1; got < entry.bytes && n > 0; got += n)
        n = fs.readSync(fd, buf, got, entry.bytes - got, entry.offset + got);
      return buf.toString('latin1', 0, got);
    } finally {
      fs.closeSync(fd);
    }
  }

  /**
   * InfluxDB has it: forget it. Its file goes, off the main thread, with its last batch; were
   * the process killed first, the file would be written again at the next start, the same
   * points at the same times, which InfluxDB keeps once.
   */
  remove(entry: SpoolEntry): void {
    this.drop(entry);
    this.release(entry);
  }

  /** InfluxDB refused it as bad data: copy it to rejected/ with the reason. Returns where. */
  reject(entry: SpoolEntry, reason: string): string {
    const target = path.join(this.rejectedDir, `${pad(entry.seq)}-${entry.points}.lp`);
    try {
      fs.writeFileSync(target, this.read(entry), 'latin1');
      fs.writeFileSync(`${target}.err`, reason + '\n');
    } catch (err) {
      this.opts.onDiskError?.('reject', err as Error);
    }
    this.remove(entry);
    return target;
  }

  /**
   * Closes the journal file: kept on disk (sealed again at the next init) if it holds a batch
   * not shipped, removed if not.
   */
  close(): void {
    this.spares.close(); // first: the last commit creates no spare
    this.commit();
    const seg = this.seg;
    if (!seg) return;
    this.seg = null;
    try {
      seg.closeSync();
      if (seg.live === 0 && this.openPoints === 0) fs.rmSync(this.journal, { force: true });
    } catch (err) {
      this.opts.onDiskError?.('close', err as Error);
    }
  }

  /** The journal for the next appends: a spare made ahead, else created here. */
  private startSegment(): Segment {
    const fd = this.spares.take(this.journal) ?? fs.openSync(this.journal, 'w');
    this.openStart = 0;
    return new Segment(this.journal, fd, this.hooks);
  }

  /** The open segment is full: into batches/ under its last batch's number (none reuses it). */
  private rotate(seg: Segment): void {
    const file = path.join(this.batchesDir, `${pad(seg.lastSeq)}-${seg.points}.lp`);
    try {
      fs.renameSync(this.journal, file);
    } catch (err) {
      this.opts.onDiskError?.('seal', err as Error);
      return seg.sync(); // it stays the journal and takes the next batches
    }
    seg.file = file;
    this.seg = null;
    seg.retire();
  }

  /** One batch of a segment left: a full segment goes with its last one, the journal when idle. */
  private release(entry: SpoolEntry): void {
    const seg = entry.segment;
    if (!seg || --seg.live > 0) return;
    if (seg === this.seg) {
      if (this.openPoints > 0 || this.held !== '') return;
      // Nothing in it is needed: the next commit starts another journal. Removed here, not off
      // the main thread, which could remove that next one (the same name) instead.
      this.seg = null;
      try {
        seg.closeSync();
        fs.rmSync(this.journal, { force: true });
      } catch (err) {
        this.opts.onDiskError?.('remove', err as Error);
      }
      return;
    }
    this.pending++;
    fs.unlink(seg.file, (err) => {
      if (err && err.code !== 'ENOENT') this.opts.onDiskError?.('remove', err);
      this.done();
    });
  }

  /** A file of one batch, already on disk (a restart's, a rewritten crashed journal). */
  private pushFile(file: string, seq: number, points: number, bytes: number, body?: string) {
    const seg = new Segment(file, null, this.hooks);
    Object.assign(seg, { size: bytes, batches: 1, points, lastSeq: seq, live: 1 });
    const entry: SpoolEntry = { seq, points, bytes, segment: seg, offset: 0, body };
    if (body === undefined) delete entry.body;
    this.push(entry);
    return entry;
  }

  private push(entry: SpoolEntry): void {
    if (entry.body !== undefined && entry.segment) {
      if (this.cached + entry.bytes > this.cacheBytes) delete entry.body;
      else this.cached += entry.bytes;
    }
    this.queue.push(entry);
    this.sealedBytes += entry.bytes;
    this.sealedPoints += entry.points;
  }

  private drop(entry: SpoolEntry): void {
    const i = this.queue.indexOf(entry);
    if (i >= 0) this.queue.splice(i, 1);
    this.sealedBytes -= entry.bytes;
    this.sealedPoints -= entry.points;
    if (entry.body !== undefined && entry.segment) this.cached -= entry.bytes;
  }
}
