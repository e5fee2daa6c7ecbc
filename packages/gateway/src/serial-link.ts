/**
 * A serial port that comes back: opens the port, and whenever it fails to open or closes
 * (unplugged, the pty's other side gone), tries again after a back-off (`backoffDelay`: doubling
 * from `backoff.minMs` to `backoff.maxMs`) that resets after a good open. The port factory is
 * injected.
 */
import { backoffDelay, type Backoff } from '@armtwin/protocol';
import { SerialPort } from 'serialport';

export interface SerialLinkOptions {
  /** Device path, e.g. /dev/ttyUSB0. */
  path: string;
  baudRate: number;
  /** Delays between tries to open the port. */
  backoff: Backoff;
}

export const DEFAULT_SERIAL_LINK_OPTIONS: Omit<SerialLinkOptions, 'path'> = {
  baudRate: 115200,
  backoff: { minMs: 250, maxMs: 5000 },
};

/** The part of `SerialPort` the link uses. */
export interface PortLike {
  readonly isOpen: boolean;
  open(cb: (err: Error | null) => void): void;
  close(cb?: (err: Error | null) => void): void;
  write(data: Buffer): boolean;
  on(event: 'data', fn: (chunk: Buffer) => void): this;
  on(event: 'close' | 'error', fn: (err?: Error | null) => void): this;
  removeAllListeners(): this;
}

export type OpenPort = (path: string, baudRate: number) => PortLike;

export const openSerialPort: OpenPort = (path, baudRate) =>
  new SerialPort({ path, baudRate, autoOpen: false }) as unknown as PortLike;

export interface SerialLinkEvents {
  onOpen(): void;
  onClose(reason: string): void;
  onData(chunk: Buffer): void;
}

export class SerialLink {
  private port: PortLike | undefined;
  private timer: NodeJS.Timeout | undefined;
  /** Failed opens (and closes) since the last good open. */
  private failures = 0;
  private stopped = false;
  readonly counters = { opens: 0, openFailures: 0, closes: 0 };
  private readonly o: SerialLinkOptions;

  constructor(
    options: Partial<SerialLinkOptions> & { path: string },
    private readonly events: SerialLinkEvents,
    private readonly openPort: OpenPort = openSerialPort,
  ) {
    this.o = { ...DEFAULT_SERIAL_LINK_OPTIONS, ...options };
  }

  get isOpen(): boolean {
    return this.port?.isOpen ?? false;
  }

  start(): void {
    this.stopped = false;
    this.tryOpen();
  }

  /** Writes verbatim; false when the port is not open (nothing is queued for later). */
  write(data: Buffer): boolean {
    if (!this.port?.isOpen) return false;
    this.port.write(data);
    return true;
  }

  async stop(): Promise<void> {
    this.stopped = true;
    clearTimeout(this.timer);
    const port = this.port;
    this.port = undefined;
    if (port?.isOpen) await new Promise<void>((resolve) => port.close(() => resolve()));
    port?.removeAllListeners();
  }

  private tryOpen(): void {
    if (this.stopped) return;
    let port: PortLike;
    try {
      port = this.openPort(this.o.path, this.o.baudRate);
    } catch (err) {
      return this.retry(err instanceof Error ? err.message : String(err));
    }
    this.port = port;
    port.on('data', (chunk) => this.events.onData(chunk));
    port.on('error', () => {}); // reported through open's callback or 'close'
    port.on('close', (err) => {
      if (this.port !== port) return;
      this.port = undefined;
      port.removeAllListeners();
      this.counters.closes++;
      this.events.onClose(err?.message ?? 'closed');
      this.retry('closed');
    });
    port.open((err) => {
      if (this.port !== port) return;
      if (err) {
        this.port = undefined;
        port.removeAllListeners();
        this.counters.openFailures++;
        return this.retry(err.message);
      }
      this.counters.opens++;
      this.failures = 0;
      this.events.onOpen();
    });
  }

  private retry(_reason: string): void {
    if (this.stopped) return;
    const delay = backoffDelay(this.failures++, this.o.backoff);
    this.timer = setTimeout(() => this.tryOpen(), delay);
  }
}
