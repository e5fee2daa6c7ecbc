/**
 * The spool's next journals, created ahead off the main thread (libuv's pool): empty files
 * `journal.next.<k>` that a seal renames to `journal.lp` instead of creating one. Creating a
 * file waits for the file system's own journal, which the seals' fsyncs keep busy, so an
 * `open(O_CREAT)` on the main thread stalled the intake (the `open` of BENCHMARKS.md §2's
 * profile). Nothing is ever written to a file under its spare name, so a crash leaves only
 * empty spares, removed at the next start.
 */
import fs from 'node:fs';
import path from 'node:path';

/** Spares kept ready: a seal every few ms at a high rate outruns a single one. */
const SPARES = 3;
const PREFIX = 'journal.next.';

export class JournalSpares {
  private readonly ready: { file: string; fd: number }[] = [];
  private opening = 0;
  private next = 0;
  private closed = false;

  /**
   * `started`/`finished` bracket each creation (the spool's `settled` waits for them); `onError`
   * gets a failed creation or rename (the spool then creates the journal itself).
   */
  constructor(
    private readonly dir: string,
    private readonly hooks: {
      started(): void;
      finished(): void;
      onError(err: Error): void;
    },
  ) {}

  /**
   * Removes spares a previous run left (always empty) and creates the first ones, here, at start.
   */
  init(): void {
    for (const name of fs.readdirSync(this.dir))
      if (name.startsWith(PREFIX)) fs.rmSync(path.join(this.dir, name), { force: true });
    while (this.ready.length < SPARES) {
      const file = this.name();
      this.ready.push({ file, fd: fs.openSync(file, 'w') });
    }
  }

  /**
   * Renames a ready spare to `journal` and returns its descriptor (open for writing, not
   * appending: the spool writes at positions); null when none is ready, or the rename failed.
   */
  take(journal: string): number | null {
    const spare = this.ready.shift();
    this.fill();
    if (!spare) return null;
    try {
      fs.renameSync(spare.file, journal);
      return spare.fd;
    } catch (err) {
      fs.closeSync(spare.fd);
      this.hooks.onError(err as Error);
      return null;
    }
  }

  /** Closes the ready spares (their empty files stay until the next init). */
  close(): void {
    this.closed = true;
    for (const s of this.ready.splice(0)) fs.closeSync(s.fd);
  }

  private name(): string {
    return path.join(this.dir, `${PREFIX}${this.next++}`);
  }

  private fill(): void {
    while (!this.closed && this.ready.length + this.opening < SPARES) {
      const file = this.name();
      this.opening++;
      this.hooks.started();
      fs.open(file, 'w', (err, fd) => {
        this.opening--;
        if (err) this.hooks.onError(err);
        else if (this.closed) fs.closeSync(fd);
        else this.ready.push({ file, fd });
        this.hooks.finished();
      });
    }
  }
}
