/**
 * The camera recording's counters (shown at `/metrics` as `armtwin_middleware_camera_*`): events
 * by kind (connects, takes, takes ended and why, segments written, segments deleted by age or
 * size, frames dropped and why) and problems by kind, each problem told to the log once.
 */
export class RecordingCounters {
  /** Events and problems by kind. */
  readonly events: Record<string, number> = {};
  frames = 0;
  bytesIn = 0;
  /** Finished segments on disk now, and their bytes. */
  segments = 0;
  bytesStored = 0;
  private readonly told = new Set<string>();

  constructor(private readonly onFirst: (kind: string, message: string) => void = () => {}) {}

  event(kind: string, n = 1): void {
    this.events[kind] = (this.events[kind] ?? 0) + n;
  }

  /** Counted under `problem-<kind>`; the first of each kind is told. */
  problem(kind: string, message: string): void {
    this.event(`problem-${kind}`);
    if (this.told.has(kind)) return;
    this.told.add(kind);
    this.onFirst(kind, message);
  }

  frame(bytes: number): void {
    this.frames++;
    this.bytesIn += bytes;
  }
}
