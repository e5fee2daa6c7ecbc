/**
 * One spool file and the batches in it (./spool.ts). A segment is first the open journal
 * (`journal.lp`): every commit appends to it, and each sealed batch is a range of it (offset,
 * bytes). At its size or batch limit it is renamed into batches/ and the next commit starts
 * another; it is removed once InfluxDB has every batch in it. So a file is created, renamed,
 * closed and unlinked once per many batches, not once per batch (BENCHMARKS.md §2).
 *
 * Its descriptor is fdatasync'd off the main thread after each seal, one sync at a time: seals
 * while one runs make one more after it (it covers them all), so a sealed batch is on the disk
 * itself once the sync that started after its seal has finished.
 */
import fs from 'node:fs';

/** The calls a segment makes off the main thread (node:fs; a script in unit tests). */
export interface SegmentIo {
  fdatasync(fd: number, cb: (err: NodeJS.ErrnoException | null) => void): void;
  close(fd: number, cb: (err: NodeJS.ErrnoException | null) => void): void;
}

export interface SegmentHooks {
  /** Disk work off the main thread begins / ends (the spool's `settled` waits for it). */
  started(): void;
  finished(): void;
  onError(op: string, err: Error): void;
}

export class Segment {
  /** Bytes written: where the next append goes (positioned writes, see Spool.commit). */
  size = 0;
  /** Batches sealed in it, their points, and the sequence number of the last one. */
  batches = 0;
  points = 0;
  lastSeq = 0;
  /** Its batches not yet shipped (or rejected): at 0, once renamed into batches/, it goes. */
  live = 0;
  private syncing = false;
  private again = false;
  private closing = false;

  constructor(
    /** Where it is now: the journal, then its name in batches/. */
    public file: string,
    /** Open for writing while it is the journal and until its last sync; null after. */
    public fd: number | null,
    private readonly hooks: SegmentHooks,
    private readonly io: SegmentIo = fs,
  ) {}

  /** fdatasync off the main thread; while one runs, one more follows it. */
  sync(): void {
    if (this.fd === null) return;
    if (this.syncing) {
      this.again = true;
      return;
    }
    this.syncing = true;
    this.hooks.started();
    this.io.fdatasync(this.fd, (err) => {
      if (err) this.hooks.onError('seal', err);
      this.syncing = false;
      if (this.again) {
        this.again = false;
        this.sync();
      } else if (this.closing) this.closeNow();
      this.hooks.finished(); // after the next step began: `settled` never sees a gap
    });
  }

  /** No more appends: a last sync covering every write, then the descriptor is closed. */
  retire(): void {
    this.closing = true;
    if (this.syncing) this.again = true;
    else this.sync();
  }

  /** Closes the descriptor now (no sync); after one in flight if there is one. */
  closeSync(): void {
    if (this.fd === null) return;
    if (this.syncing) {
      this.closing = true;
      this.again = false;
      return;
    }
    const fd = this.fd;
    this.fd = null;
    fs.closeSync(fd);
  }

  private closeNow(): void {
    const fd = this.fd;
    if (fd === null) return;
    this.fd = null;
    this.hooks.started();
    this.io.close(fd, (err) => {
      if (err) this.hooks.onError('close', err);
      this.hooks.finished();
    });
  }
}
