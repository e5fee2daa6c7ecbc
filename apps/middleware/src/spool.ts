/**
 * The durable spool: every point is on disk before its MQTT message is acknowledged, and
 * stays there until InfluxDB has it.
 *
 *   <dir>/journal.lp                 the open batch: one append (write(2)) per commit, i.e. per
 *                                    event-loop turn of MQTT messages (../README.md § Spool)
 *   <dir>/batches/<seq>-<n>.lp       sealed batches of n points, oldest = smallest seq
 *   <dir>/rejected/<seq>-<n>.lp(.err) batches InfluxDB refused as bad data, with the reason
 *
 * A batch is sealed (rename, then fsync off the main thread) at BATCH_SIZE points or
 * FLUSH_INTERVAL_MS; the shipper
 * writes sealed batches oldest-first and unlinks each once InfluxDB accepted it. On start, a
 * journal left by a crash is sealed first (a torn last line, never acknowledged, is cut), so
 * a restarted middleware replays everything. The appends are not fsync'd one by one: a
 * SIGKILL loses nothing (the page cache survives), a power cut can lose the open batch and a
 * batch sealed in the last milliseconds whose fsync had not finished.
 *
 * The next journal is created ahead, off the main thread (./journal-spares.ts): the first commit
 * after a seal renames a ready empty file to `journal.lp`, and creates one only if none is ready.
 *
 * `hold` takes a message's lines into memory, `commit` appends everything held in one write;
 * the MQTT edge acknowledges the messages of a commit only after it (src/mqtt.ts). `append` is
 * both at once.
 */
import fs from 'node:fs';
import path from 'node:path';
import { JournalSpares } from './journal-spares.ts';

export interface SpoolEntry {
  seq: number;
  points: number;
  bytes: number;
  /** The file; null if the disk failed and the batch lives only in memory. */
  file: string | null;
  /** The body, when cached in memory. */
  body?: string;
}

export interface SpoolOptions {
  dir: string;
  /** Bound on sealed + open bytes; `full` beyond it. */
  maxBytes: number;
  /** Bodies of at most this many bytes in total are cached in memory (the rest re-read). */
  cacheBytes?: number;
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
  private fd: number | null = null;
  private nextSeq = 1;
  /** The open batch's text (for the cache), and its tail not yet written to the journal. */
  private open = '';
  private held = '';
  private openPoints = 0;
  private openBytes = 0;
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
    this.spares = new JournalSpares(opts.dir, {
      started: () => this.pending++,
      finished: () => this.done(),
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
      this.push({ seq: Number(m[1]), points: Number(m[2]), bytes: fs.statSync(file).size, file });
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

  /** Writes what `hold` took since the last commit to the journal, in one write. */
  commit(): void {
    if (this.held === '') return;
    const body = this.held;
    this.held = '';
    this.open += body;
    try {
      this.fd ??= this.spares.take(this.journal) ?? fs.openSync(this.journal, 'a');
      fs.writeSync(this.fd, body, null, 'latin1');
    } catch (err) {
      this.opts.onDiskError?.('append', err as Error);
    }
  }

  /**
   * Seals the open batch into the queue; null if it was empty. The journal is renamed into
   * batches/ at once and fsync'd off the main thread (libuv's pool), so a seal never blocks
   * intake on the disk; the batch can be shipped meanwhile (its bytes are in the page cache).
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
    const file = path.join(this.batchesDir, `${pad(seq)}-${points}.lp`);
    let entry: SpoolEntry = { seq, points, bytes: body.length, file: null, body };
    try {
      if (this.fd === null) throw new Error('journal not open');
      const fd = this.fd;
      this.fd = null;
      fs.renameSync(this.journal, file);
      entry = { ...entry, file };
      this.pending++;
      fs.fdatasync(fd, (err) => {
        if (err) this.opts.onDiskError?.('seal', err);
        fs.close(fd, () => this.done());
      });
    } catch (err) {
      this.opts.onDiskError?.('seal', err as Error);
      this.closeJournal(true);
    }
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

  /** Adds a whole batch as a sealed file (sync mode's failed writes). */
  writeSealed(body: string, points: number): SpoolEntry {
    const seq = this.nextSeq++;
    const file = path.join(this.batchesDir, `${pad(seq)}-${points}.lp`);
    let entry: SpoolEntry = { seq, points, bytes: body.length, file: null, body };
    try {
      const tmp = `${file}.tmp`;
      const fd = fs.openSync(tmp, 'w');
      fs.writeSync(fd, body, null, 'latin1');
      fs.fsyncSync(fd);
      fs.closeSync(fd);
      fs.renameSync(tmp, file);
      entry = { ...entry, file };
    } catch (err) {
      this.opts.onDiskError?.('write', err as Error);
    }
    this.push(entry);
    return entry;
  }

  /** The oldest sealed batch. */
  peek(): SpoolEntry | undefined {
    return this.queue[0];
  }

  read(entry: SpoolEntry): string {
    return entry.body ?? fs.readFileSync(entry.file!, 'latin1');
  }

  /**
   * InfluxDB has it: forget it. The file goes off the main thread; were the process killed
   * first, the batch would be written again at the next start, the same points at the same
   * times, which InfluxDB keeps once.
   */
  remove(entry: SpoolEntry): void {
    this.drop(entry);
    if (!entry.file) return;
    this.pending++;
    fs.unlink(entry.file, (err) => {
      if (err && err.code !== 'ENOENT') this.opts.onDiskError?.('remove', err);
      this.done();
    });
  }

  /** InfluxDB refused it as bad data: move it to rejected/ with the reason. Returns where. */
  reject(entry: SpoolEntry, reason: string): string {
    this.drop(entry);
    const target = path.join(this.rejectedDir, `${pad(entry.seq)}-${entry.points}.lp`);
    try {
      if (entry.file) fs.renameSync(entry.file, target);
      else fs.writeFileSync(target, entry.body ?? '', 'latin1');
      fs.writeFileSync(`${target}.err`, reason + '\n');
    } catch (err) {
      this.opts.onDiskError?.('reject', err as Error);
    }
    return target;
  }

  /** Closes the journal file (keeps it on disk: sealed again at the next init). */
  close(): void {
    this.spares.close(); // first: the last commit creates no spare
    this.commit();
    this.closeJournal(false);
  }

  private closeJournal(removeFile: boolean): void {
    try {
      if (this.fd !== null) fs.closeSync(this.fd);
      if (removeFile) fs.rmSync(this.journal, { force: true });
    } catch {
      // already reported by the caller
    }
    this.fd = null;
  }

  private push(entry: SpoolEntry): void {
    if (entry.body !== undefined && entry.file) {
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
    if (entry.body !== undefined && entry.file) this.cached -= entry.bytes;
  }
}
